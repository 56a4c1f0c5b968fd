// A pattern's stored arrays: found by name or component, their shape, and decoded.
#include "ready/reading.hpp"

#include <cmath>
#include <limits>
#include <string_view>

#include "description/integer_text.hpp"
#include "description/plain_name.hpp"
#include "ready/pattern.hpp"
#include "sim/formula/rule.hpp"

namespace ready::reading {

using description::printable_short;

namespace {

// The file's arrays, decoded whichever way VTK wrote them.
struct ArrayReader {
    const XMLElement* vtk;
    const std::string& raw;  // appended raw data
    vtk::Encoding enc;
    std::uint64_t cells;

    // `array`'s values, `components` a cell; sets `float64` to its type.
    std::vector<double> read(const XMLElement* array, int components, bool& float64) const {
        const std::string name = "<DataArray Name=\"" + printable_short(text_attribute(array, "Name", ""), 20) + "\">";
        const std::string t = text_attribute(array, "type", "");
        if (t != "Float32" && t != "Float64")
            throw Refused(name + " is type \"" + printable_short(t, 20) + "\": figgen reads Float32 and Float64");
        float64 = t == "Float64";
        const std::uint64_t count = cells * static_cast<std::uint64_t>(components);
        const std::uint64_t bytes = count * (float64 ? 8 : 4);
        const std::string format = text_attribute(array, "format", "ascii");
        const std::string_view text = array->GetText() ? array->GetText() : "";
        std::vector<double> values;
        try {
            if (format == "ascii") {
                values = vtk::decode_ascii(text, count, float64);
            } else if (format == "binary") {
                values = vtk::numbers_of(vtk::decode_base64(text, enc, bytes), float64);
            } else if (format == "appended") {
                values = appended(array, name, bytes, float64);
            } else {
                throw Refused(name + "'s format is \"" + printable_short(format, 20) +
                              "\": figgen reads ascii, binary and appended");
            }
        } catch (const vtk::DataError& e) {
            throw Refused(name + ": " + e.what());
        }
        for (double v : values)
            if (!std::isfinite(v)) throw Refused(name + " holds a value that is not a finite number");
        return values;
    }

    std::vector<double> appended(const XMLElement* array, const std::string& name, std::uint64_t bytes,
                                 bool float64) const {
        const XMLElement* data = child(vtk, "AppendedData");
        if (!data) throw Refused(name + " is appended, but there is no <AppendedData>");
        const std::string offset_text = text_attribute(array, "offset", "");
        const auto offset = description::integer_text(offset_text, 0, std::numeric_limits<long long>::max());
        if (!offset) throw Refused(name + "'s offset is \"" + printable_short(offset_text, 20) + "\", not an integer >= 0");
        const std::string encoding = text_attribute(data, "encoding", "");
        if (encoding == "raw") {
            if (static_cast<unsigned long long>(*offset) > raw.size()) throw Refused(name + "'s offset is past the data");
            const std::string_view from = std::string_view(raw).substr(static_cast<std::size_t>(*offset));
            return vtk::numbers_of(vtk::decode_raw(from, enc, bytes), float64);
        }
        if (encoding == "base64") {
            std::string_view text = data->GetText() ? data->GetText() : "";
            const std::size_t mark = text.find('_');
            if (mark == std::string_view::npos) throw Refused("<AppendedData> has no '_' before its data");
            text.remove_prefix(mark + 1);
            if (static_cast<unsigned long long>(*offset) > text.size()) throw Refused(name + "'s offset is past the data");
            return vtk::numbers_of(vtk::decode_base64(text.substr(static_cast<std::size_t>(*offset)), enc, bytes), float64);
        }
        throw Refused("<AppendedData encoding> is \"" + printable_short(encoding, 20) + "\": figgen reads raw and base64");
    }
};

}  // namespace

StoredArrays stored_arrays(const XMLElement* piece, int chemicals) {
    StoredArrays s;
    std::vector<const XMLElement*> all;
    for (const XMLElement* a = child(child(piece, "PointData"), "DataArray"); a; a = a->NextSiblingElement("DataArray"))
        all.push_back(a);
    for (int c = 0; c < chemicals; ++c)
        for (const XMLElement* a : all)
            if (text_attribute(a, "Name", "") == sim::formula::chemical_name(c)) {
                s.named.push_back(a);
                break;
            }
    if (static_cast<int>(s.named.size()) != chemicals || static_cast<int>(all.size()) != chemicals) s.named.clear();
    if (s.named.empty() && all.size() == 1 && integer(all[0], "NumberOfComponents", 1, 1, 64) == chemicals)
        s.components = all[0];
    // The number type is the arrays' (Ready's too), whether or not they are decoded.
    if (s.found()) s.float64 = text_attribute(s.named.empty() ? s.components : s.named[0], "type", "") == "Float64";
    return s;
}

std::string no_arrays(int chemicals) {
    return "it starts from its stored arrays, but holds neither arrays a, b, ... nor one of " +
           std::to_string(chemicals) + " components";
}

std::shared_ptr<description::StoredStart> start_shape(const StoredArrays& stored, const Grid& grid, int chemicals) {
    auto start = std::make_shared<description::StoredStart>();
    start->width = static_cast<int>(grid.width);
    start->height = static_cast<int>(grid.height);
    start->depth = static_cast<int>(grid.depth);
    start->chemical_count = chemicals;
    start->float64 = stored.float64;
    return start;
}

std::shared_ptr<description::StoredStart> decode_start(const StoredArrays& stored, const XMLElement* vtk,
                                                       const std::string& raw, vtk::Encoding enc, const Grid& grid,
                                                       int chemicals) {
    const ArrayReader reader{vtk, raw, enc, static_cast<std::uint64_t>(grid.width * grid.height * grid.depth)};
    const double bytes = 8.0 * static_cast<double>(reader.cells) * chemicals;
    if (bytes > static_cast<double>(max_start_bytes))
        throw Refused("its stored arrays would take " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                      " MiB as doubles: figgen reads at most " + std::to_string(max_start_bytes >> 20) +
                      " MiB of a pattern's arrays");
    if (!stored.found()) throw Refused(no_arrays(chemicals));
    auto start = start_shape(stored, grid, chemicals);
    if (!stored.named.empty()) {
        for (const XMLElement* a : stored.named) start->chemicals.push_back(reader.read(a, 1, start->float64));
        return start;
    }
    const std::vector<double> v = reader.read(stored.components, chemicals, start->float64);
    start->chemicals.assign(static_cast<std::size_t>(chemicals), std::vector<double>(reader.cells));
    for (std::uint64_t i = 0; i < reader.cells; ++i)
        for (int c = 0; c < chemicals; ++c)
            start->chemicals[static_cast<std::size_t>(c)][i] = v[i * static_cast<std::uint64_t>(chemicals) + c];
    return start;
}

}  // namespace ready::reading
