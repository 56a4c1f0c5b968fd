#include "ready/vtu.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "description/integer_text.hpp"
#include "description/plain_name.hpp"

namespace ready::vtu {
namespace {

using description::printable_short;
using tinyxml2::XMLElement;
namespace cell_type = sim::mesh::cell_type;

std::string attribute_text(const XMLElement* e, const char* name, const std::string& fallback) {
    const char* text = e->Attribute(name);
    if (!text) return fallback;
    std::string_view s = text;
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return std::string(s);
}

// "<Piece NumberOfCells>" and such: an element and its attribute, as messages name them.
std::string named(const std::string& element, const char* attribute) {
    return "<" + element + " " + attribute + ">";
}

// An integer attribute from `low` to `high`.
std::uint64_t count_attribute(const XMLElement* e, const char* name, std::uint64_t high, std::uint64_t fallback,
                              bool required) {
    const std::string where = named(e->Name(), name);
    if (!e->Attribute(name)) {
        if (required) throw DataError("no " + where);
        return fallback;
    }
    const std::string text = attribute_text(e, name, "");
    const auto v = description::integer_text(text, 0, static_cast<long long>(high));
    if (!v)
        throw DataError(where + " is \"" + printable_short(text, 20) + "\", not an integer from 0 to " +
                        std::to_string(high));
    return static_cast<std::uint64_t>(*v);
}

// The parts of a file: its XML, and the raw appended bytes cut out of it
// (they are not XML: tinyxml2 would stop at their first NUL).
struct Parsed {
    tinyxml2::XMLDocument xml;
    std::string raw;  // appended raw data, after its '_'
};

void parse(std::string_view text, Parsed& p) {
    std::string xml(text);
    const std::size_t tag = text.find("<AppendedData");
    if (tag != std::string_view::npos) {
        const std::size_t close = text.find('>', tag);
        if (close == std::string_view::npos) throw DataError("<AppendedData> is not closed");
        if (text.substr(tag, close - tag).find("\"raw\"") != std::string_view::npos) {
            const std::size_t mark = text.find('_', close);
            const std::size_t end = text.rfind("</AppendedData>");
            if (mark == std::string_view::npos || end == std::string_view::npos || end < mark)
                throw DataError("<AppendedData encoding=\"raw\"> has no data between '_' and </AppendedData>");
            p.raw = std::string(text.substr(mark + 1, end - mark - 1));
            xml = std::string(text.substr(0, mark)).append(text.substr(end));
        }
    }
    // tinyxml2's own message quotes the text it stopped at: its error's name and line only.
    if (p.xml.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
        throw DataError("not well-formed XML (line " + std::to_string(p.xml.ErrorLineNum()) + ": " +
                        tinyxml2::XMLDocument::ErrorIDToName(p.xml.ErrorID()) + ")");
}

// How the file stores its arrays: <VTKFile byte_order header_type compressor>.
vtk::Encoding encoding_of(const XMLElement* vtk) {
    const std::string order = attribute_text(vtk, "byte_order", "LittleEndian");
    if (order != "LittleEndian")
        throw DataError("<VTKFile byte_order> is \"" + printable_short(order, 20) + "\": figgen reads LittleEndian");
    vtk::Encoding enc;
    const std::string header = attribute_text(vtk, "header_type", "UInt32");
    if (header == "UInt64") enc.header = 8;
    else if (header != "UInt32")
        throw DataError("<VTKFile header_type> is \"" + printable_short(header, 20) + "\": figgen reads UInt32 and UInt64");
    const std::string compressor = attribute_text(vtk, "compressor", "");
    if (compressor == "vtkZLibDataCompressor") enc.compressed = true;
    else if (!compressor.empty())
        throw DataError("<VTKFile compressor> is \"" + printable_short(compressor, 30) +
                        "\": figgen reads vtkZLibDataCompressor or none");
    return enc;
}

// The file's arrays, decoded whichever way VTK wrote them, within one
// budget of decoded bytes for them all.
class Arrays {
public:
    Arrays(const XMLElement* vtk, const std::string& raw) : vtk_(vtk), raw_(raw), enc_(encoding_of(vtk)) {}

    // `count` numbers of a Float32 or Float64 array; sets `float64`.
    std::vector<double> floats(const XMLElement* a, const std::string& name, std::uint64_t count, bool& float64) {
        const std::string t = attribute_text(a, "type", "");
        if (t != "Float32" && t != "Float64")
            throw DataError(name + " is type \"" + printable_short(t, 20) + "\": figgen reads Float32 and Float64 there");
        float64 = t == "Float64";
        std::vector<double> values;
        decode(a, name, count, float64 ? 8 : 4, [&](const std::vector<std::uint8_t>* bytes, std::string_view text) {
            values = bytes ? vtk::numbers_of(*bytes, float64) : vtk::decode_ascii(text, count, float64);
        });
        for (double v : values)
            if (!std::isfinite(v)) throw DataError(name + " holds a value that is not a finite number");
        return values;
    }

    // `count` numbers of an integer array (Int8 to UInt64).
    std::vector<std::int64_t> integers(const XMLElement* a, const std::string& name, std::uint64_t count) {
        const std::string t = attribute_text(a, "type", "");
        const auto type = vtk::integer_type(t);
        if (!type) throw DataError(name + " is type \"" + printable_short(t, 20) + "\": figgen reads Int8 to UInt64 there");
        std::vector<std::int64_t> values;
        decode(a, name, count, static_cast<std::uint64_t>(type->bytes),
               [&](const std::vector<std::uint8_t>* bytes, std::string_view text) {
                   values = bytes ? vtk::integers_of(*bytes, *type) : vtk::decode_ascii_integers(text, count, *type);
               });
        return values;
    }

private:
    const XMLElement* vtk_;
    const std::string& raw_;
    vtk::Encoding enc_;
    std::uint64_t decoded_ = 0;

    // Hands `use` the array's bytes, or its text when it is ascii.
    template <class Use>
    void decode(const XMLElement* a, const std::string& name, std::uint64_t count, std::uint64_t size, Use&& use) {
        // count <= 2^40 (counts and offsets are bounded before they get here), size <= 8: no wrap.
        const std::uint64_t bytes = count * size;
        if (bytes > max_decoded_bytes - decoded_)
            throw DataError(name + " would take the file's arrays past " + std::to_string(max_decoded_bytes >> 20) +
                            " MiB decoded: figgen reads at most that");
        decoded_ += bytes;
        const std::string format = attribute_text(a, "format", "ascii");
        const std::string_view text = a->GetText() ? a->GetText() : "";
        try {
            if (format == "ascii") {
                use(nullptr, text);
            } else if (format == "binary") {
                const auto b = vtk::decode_base64(text, enc_, bytes);
                use(&b, {});
            } else if (format == "appended") {
                const auto b = appended(a, name, bytes);
                use(&b, {});
            } else {
                throw DataError(name + "'s format is \"" + printable_short(format, 20) +
                                "\": figgen reads ascii, binary and appended");
            }
        } catch (const vtk::DataError& e) {
            const std::string what = e.what();
            if (what.rfind(name, 0) == 0) throw;  // named already
            throw DataError(name + ": " + what);
        }
    }

    std::vector<std::uint8_t> appended(const XMLElement* a, const std::string& name, std::uint64_t bytes) const {
        const XMLElement* data = vtk_->FirstChildElement("AppendedData");
        if (!data) throw DataError(name + " is appended, but there is no <AppendedData>");
        const std::string offset_text = attribute_text(a, "offset", "");
        const auto offset = description::integer_text(offset_text, 0, std::numeric_limits<long long>::max());
        if (!offset)
            throw DataError(name + "'s offset is \"" + printable_short(offset_text, 20) + "\", not an integer >= 0");
        const std::string encoding = attribute_text(data, "encoding", "");
        if (encoding == "raw") {
            if (static_cast<unsigned long long>(*offset) > raw_.size()) throw DataError(name + "'s offset is past the data");
            return vtk::decode_raw(std::string_view(raw_).substr(static_cast<std::size_t>(*offset)), enc_, bytes);
        }
        if (encoding == "base64") {
            std::string_view text = data->GetText() ? data->GetText() : "";
            const std::size_t mark = text.find('_');
            if (mark == std::string_view::npos) throw DataError("<AppendedData> has no '_' before its data");
            text.remove_prefix(mark + 1);
            if (static_cast<unsigned long long>(*offset) > text.size()) throw DataError(name + "'s offset is past the data");
            return vtk::decode_base64(text.substr(static_cast<std::size_t>(*offset)), enc_, bytes);
        }
        throw DataError("<AppendedData encoding> is \"" + printable_short(encoding, 20) + "\": figgen reads raw and base64");
    }
};

std::string array_name(const XMLElement* a) {
    return "<DataArray Name=\"" + printable_short(attribute_text(a, "Name", ""), 20) + "\">";
}

const XMLElement* named_array(const XMLElement* cells, const char* name) {
    for (const XMLElement* a = cells->FirstChildElement("DataArray"); a; a = a->NextSiblingElement("DataArray"))
        if (attribute_text(a, "Name", "") == name) return a;
    return nullptr;
}

void check_components(const XMLElement* a, const std::string& name, std::uint64_t want) {
    const std::uint64_t got = count_attribute(a, "NumberOfComponents", 1'000'000, 1, false);
    if (got != want)
        throw DataError(name + "'s NumberOfComponents is " + std::to_string(got) + ", not " + std::to_string(want));
}

const char* type_name(std::int64_t type) {
    switch (type) {
    case cell_type::triangle: return "VTK_TRIANGLE";
    case cell_type::polygon: return "VTK_POLYGON";
    case cell_type::quad: return "VTK_QUAD";
    case cell_type::tetra: return "VTK_TETRA";
    case cell_type::voxel: return "VTK_VOXEL";
    case cell_type::hexahedron: return "VTK_HEXAHEDRON";
    case cell_type::wedge: return "VTK_WEDGE";
    case cell_type::pyramid: return "VTK_PYRAMID";
    case cell_type::polyhedron: return "VTK_POLYHEDRON";
    default: return nullptr;
    }
}

// The points a cell of `type` has: exactly `least`, or (polygons and
// polyhedra) from `least` to max_cell_points.
std::pair<std::int64_t, bool> points_of_type(std::int64_t type) {
    switch (type) {
    case cell_type::triangle: return {3, true};
    case cell_type::quad:
    case cell_type::tetra: return {4, true};
    case cell_type::voxel:
    case cell_type::hexahedron: return {8, true};
    case cell_type::wedge: return {6, true};
    case cell_type::pyramid: return {5, true};
    case cell_type::polygon: return {3, false};
    default: return {4, false};  // polyhedron
    }
}

void read_cells(const XMLElement* cells_element, Arrays& arrays, std::uint64_t cells, std::uint64_t points,
                sim::mesh::Mesh& mesh) {
    const auto required = [&](const char* name) {
        const XMLElement* a = named_array(cells_element, name);
        if (!a) throw DataError("<Cells> has no <DataArray Name=\"" + std::string(name) + "\">");
        check_components(a, array_name(a), 1);
        return a;
    };
    const XMLElement* types_array = required("types");
    const XMLElement* offsets_array = required("offsets");
    const XMLElement* connectivity_array = required("connectivity");
    const std::string types_name = array_name(types_array), offsets_name = array_name(offsets_array),
                      connectivity_name = array_name(connectivity_array);

    const std::vector<std::int64_t> types = arrays.integers(types_array, types_name, cells);
    bool polyhedra = false;
    for (std::size_t c = 0; c < types.size(); ++c) {
        if (!type_name(types[c]))
            throw DataError(types_name + " gives cell " + std::to_string(c) + " type " + std::to_string(types[c]) +
                            ": figgen reads VTK's types 5 (triangle), 7 (polygon), 9 (quad), 10 (tetra), 11 (voxel), "
                            "12 (hexahedron), 13 (wedge), 14 (pyramid) and 42 (polyhedron)");
        polyhedra = polyhedra || types[c] == cell_type::polyhedron;
    }
    // VTK's offsets: where each cell's points end in the connectivity.
    const std::vector<std::int64_t> ends = arrays.integers(offsets_array, offsets_name, cells);
    std::int64_t before = 0;
    for (std::size_t c = 0; c < ends.size(); ++c) {
        if (ends[c] < before)
            throw DataError(offsets_name + " gives cell " + std::to_string(c) + " the end " + std::to_string(ends[c]) +
                            ", before the previous cell's " + std::to_string(before) + ": the offsets must increase");
        const std::int64_t n = ends[c] - before;  // no wrap: ends[c] >= before >= 0
        const auto [least, exact] = points_of_type(types[c]);
        if (n < least || n > sim::mesh::max_cell_points || (exact && n != least))
            throw DataError(offsets_name + " gives cell " + std::to_string(c) + " (" + type_name(types[c]) + ") " +
                            std::to_string(n) + " points: it has " +
                            (exact ? std::to_string(least)
                                   : std::to_string(least) + " to " + std::to_string(sim::mesh::max_cell_points)));
        before = ends[c];
    }
    const auto connectivity_count = static_cast<std::uint64_t>(before);  // <= 64 cells: checked above
    mesh.point_ids = arrays.integers(connectivity_array,
                                     connectivity_name + " (of " + std::to_string(connectivity_count) +
                                         " point indices, as the last offset says)",
                                     connectivity_count);
    for (std::size_t i = 0, c = 0; i < mesh.point_ids.size(); ++i) {
        while (static_cast<std::int64_t>(i) >= ends[c]) ++c;
        const std::int64_t p = mesh.point_ids[i];
        if (p < 0 || static_cast<std::uint64_t>(p) >= points)
            throw DataError(connectivity_name + " gives cell " + std::to_string(c) + " the point " + std::to_string(p) +
                            ": <Piece NumberOfPoints> is " + std::to_string(points) + ", so indices run from 0 to " +
                            std::to_string(static_cast<std::int64_t>(points) - 1));
    }
    mesh.offsets.assign(1, 0);
    mesh.offsets.insert(mesh.offsets.end(), ends.begin(), ends.end());
    mesh.types.assign(types.begin(), types.end());  // each checked: 5 to 42

    // Polyhedra's faces: faceoffsets, where each cell's faces end in faces
    // (-1 for other cells), and faces, as long as the last of them says
    // (VTK's reader reads them so).
    const XMLElement* faces_array = named_array(cells_element, "faces");
    const XMLElement* face_offsets_array = named_array(cells_element, "faceoffsets");
    if (!faces_array || !face_offsets_array) {
        if (polyhedra)
            throw DataError("<Cells> holds polyhedra (type 42), but not both <DataArray Name=\"faces\"> and "
                            "<DataArray Name=\"faceoffsets\">");
        return;
    }
    check_components(face_offsets_array, array_name(face_offsets_array), 1);
    check_components(faces_array, array_name(faces_array), 1);
    mesh.face_offsets = arrays.integers(face_offsets_array, array_name(face_offsets_array), cells);
    std::int64_t length = 0;
    for (std::int64_t o : mesh.face_offsets) {
        if (o < -1)
            throw DataError(array_name(face_offsets_array) + " holds " + std::to_string(o) +
                            ": an offset is -1 (not a polyhedron) or where a polyhedron's faces end");
        length = std::max(length, o);
    }
    // Each polyhedron's faces take at most 1 + 256 faces of 1 + 64 numbers.
    const std::uint64_t most = cells * static_cast<std::uint64_t>(1 + sim::mesh::max_cell_faces * (1 + sim::mesh::max_cell_points));
    if (static_cast<std::uint64_t>(length) > most)
        throw DataError(array_name(face_offsets_array) + " gives the faces " + std::to_string(length) +
                        " numbers; " + std::to_string(cells) + " cells take at most " + std::to_string(most));
    mesh.faces = arrays.integers(faces_array, array_name(faces_array), static_cast<std::uint64_t>(length));
}

}  // namespace

UnstructuredGrid read_vtu(std::string_view text) {
    if (text.size() > max_file_bytes)
        throw DataError("a mesh file is at most " + std::to_string(max_file_bytes >> 20) + " MiB; this one is larger");
    Parsed p;
    parse(text, p);
    const XMLElement* vtk = p.xml.FirstChildElement("VTKFile");
    if (!vtk) throw DataError("no <VTKFile>: not a VTK XML file");
    const std::string type = attribute_text(vtk, "type", "");
    if (type != "UnstructuredGrid")
        throw DataError("<VTKFile type> is \"" + printable_short(type, 30) + "\", not UnstructuredGrid");
    const XMLElement* grid_element = vtk->FirstChildElement("UnstructuredGrid");
    if (!grid_element) throw DataError("no <UnstructuredGrid> in <VTKFile>");
    const XMLElement* piece = grid_element->FirstChildElement("Piece");
    if (!piece) throw DataError("no <Piece> in <UnstructuredGrid>");
    if (piece->NextSiblingElement("Piece")) throw DataError("<UnstructuredGrid> has more than one <Piece>: figgen reads one");
    const std::uint64_t points = count_attribute(piece, "NumberOfPoints", max_points, 0, true);
    const std::uint64_t cells = count_attribute(piece, "NumberOfCells", max_cells, 0, true);

    UnstructuredGrid out;
    Arrays arrays(vtk, p.raw);
    if (points > 0) {
        const XMLElement* points_element = piece->FirstChildElement("Points");
        const XMLElement* a = points_element ? points_element->FirstChildElement("DataArray") : nullptr;
        if (!a) throw DataError("<Piece NumberOfPoints> is " + std::to_string(points) + ", but there is no <Points> <DataArray>");
        const std::string name = "<Points> " + array_name(a);
        check_components(a, name, 3);
        out.mesh.points = arrays.floats(a, name, points * 3, out.points_float64);
    }
    if (cells > 0) {
        const XMLElement* cells_element = piece->FirstChildElement("Cells");
        if (!cells_element) throw DataError("<Piece NumberOfCells> is " + std::to_string(cells) + ", but there is no <Cells>");
        read_cells(cells_element, arrays, cells, points, out.mesh);
    }
    try {
        sim::mesh::check(out.mesh);  // what is left: the polyhedra's faces against their offsets and points
    } catch (const std::invalid_argument& e) {
        std::string what = e.what();
        if (what.rfind("mesh: ", 0) == 0) what.erase(0, 6);
        throw DataError("<Cells>: " + what);
    }

    if (const XMLElement* cell_data = piece->FirstChildElement("CellData")) {
        for (const XMLElement* a = cell_data->FirstChildElement("DataArray"); a; a = a->NextSiblingElement("DataArray")) {
            CellArray array;
            array.name = attribute_text(a, "Name", "");
            const std::string name = "<CellData> " + array_name(a);
            array.components = static_cast<int>(count_attribute(a, "NumberOfComponents", 64, 1, false));
            if (array.components < 1) throw DataError(name + "'s NumberOfComponents is 0, not 1 to 64");
            array.values = arrays.floats(a, name, cells * static_cast<std::uint64_t>(array.components), array.float64);
            out.cell_data.push_back(std::move(array));
        }
    }
    if (const XMLElement* rd = vtk->FirstChildElement("RD")) {
        tinyxml2::XMLPrinter printer;
        rd->Accept(&printer);
        out.rd.assign(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
    }
    return out;
}

std::string write_vtu(const UnstructuredGrid& g) {
    const sim::mesh::Mesh& m = g.mesh;
    sim::mesh::check(m);
    const std::size_t cells = m.cell_count();
    for (const CellArray& a : g.cell_data)
        if (a.components < 1 || a.components > 64 || a.values.size() != cells * static_cast<std::size_t>(a.components))
            throw std::invalid_argument("write_vtu: cell array \"" + printable_short(a.name, 20) + "\" holds " +
                                        std::to_string(a.values.size()) + " values for " + std::to_string(cells) +
                                        " cells of " + std::to_string(a.components) + " components");
    std::string rd_text;
    if (!g.rd.empty()) {
        tinyxml2::XMLDocument rd;
        const XMLElement* root = rd.Parse(g.rd.data(), g.rd.size()) == tinyxml2::XML_SUCCESS ? rd.RootElement() : nullptr;
        if (!root || std::string_view(root->Name()) != "RD" || root->NextSiblingElement())
            throw std::invalid_argument("write_vtu: rd is not one <RD> element");
        tinyxml2::XMLPrinter printer;
        root->Accept(&printer);
        rd_text.assign(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
    }

    // The arrays' texts, in the order their elements come below.
    const vtk::IntegerType int64{8, true}, uint8{1, false};
    std::vector<std::string> texts;
    tinyxml2::XMLDocument doc;
    doc.InsertEndChild(doc.NewDeclaration());
    XMLElement* vtk = doc.NewElement("VTKFile");
    doc.InsertEndChild(vtk);
    vtk->SetAttribute("type", "UnstructuredGrid");
    vtk->SetAttribute("version", "1.0");
    vtk->SetAttribute("byte_order", "LittleEndian");
    vtk->SetAttribute("header_type", "UInt64");
    vtk->SetAttribute("compressor", "vtkZLibDataCompressor");
    XMLElement* piece = vtk->InsertNewChildElement("UnstructuredGrid")->InsertNewChildElement("Piece");
    piece->SetAttribute("NumberOfPoints", static_cast<std::int64_t>(m.point_count()));
    piece->SetAttribute("NumberOfCells", static_cast<std::int64_t>(cells));
    piece->InsertNewChildElement("PointData");
    const auto array = [&](XMLElement* parent, const char* type, const std::string& name, int components) {
        XMLElement* a = parent->InsertNewChildElement("DataArray");
        a->SetAttribute("type", type);
        a->SetAttribute("Name", name.c_str());
        if (components != 1) a->SetAttribute("NumberOfComponents", components);
        a->SetAttribute("format", "binary");
        return a;
    };
    XMLElement* cell_data = piece->InsertNewChildElement("CellData");
    for (const CellArray& a : g.cell_data) {
        XMLElement* e = array(cell_data, a.float64 ? "Float64" : "Float32", a.name, a.components);
        if (a.components == 1 && !a.values.empty()) {
            const auto [lo, hi] = std::minmax_element(a.values.begin(), a.values.end());
            e->SetAttribute("RangeMin", *lo);
            e->SetAttribute("RangeMax", *hi);
        }
        texts.push_back(vtk::encode_zlib_base64(a.values, a.float64));
    }
    array(piece->InsertNewChildElement("Points"), g.points_float64 ? "Float64" : "Float32", "Points", 3);
    texts.push_back(vtk::encode_zlib_base64(m.points, g.points_float64));
    XMLElement* cells_element = piece->InsertNewChildElement("Cells");
    array(cells_element, "Int64", "connectivity", 1);
    texts.push_back(vtk::encode_zlib_base64_integers(m.point_ids, int64));
    array(cells_element, "Int64", "offsets", 1);
    texts.push_back(vtk::encode_zlib_base64_integers(std::vector<std::int64_t>(m.offsets.begin() + 1, m.offsets.end()), int64));
    array(cells_element, "UInt8", "types", 1);
    texts.push_back(vtk::encode_zlib_base64_integers(std::vector<std::int64_t>(m.types.begin(), m.types.end()), uint8));
    if (std::find(m.types.begin(), m.types.end(), cell_type::polyhedron) != m.types.end()) {
        array(cells_element, "Int64", "faces", 1);
        texts.push_back(vtk::encode_zlib_base64_integers(m.faces, int64));
        array(cells_element, "Int64", "faceoffsets", 1);
        texts.push_back(vtk::encode_zlib_base64_integers(m.face_offsets, int64));
    }

    tinyxml2::XMLPrinter printer;
    doc.Print(&printer);
    const std::string_view printed(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
    // Each array's text goes into its element after the document is
    // printed, so that the printer neither copies nor scans megabytes of
    // it; the <RD> goes in before <UnstructuredGrid>. Nothing of the
    // caller's is in what is searched but attribute values, whose '<' the
    // printer writes as "&lt;": each "<DataArray " found is one put there.
    std::string out;
    std::size_t total = printed.size() + rd_text.size() + 64;
    for (const std::string& t : texts) total += t.size() + 16;
    out.reserve(total);
    const std::size_t grid_at = printed.find("<UnstructuredGrid");
    if (grid_at == std::string_view::npos) throw std::logic_error("write_vtu: no <UnstructuredGrid> where it was put");
    std::size_t line = printed.rfind('\n', grid_at);
    line = line == std::string_view::npos ? grid_at : line + 1;
    out.append(printed.substr(0, line));
    if (!rd_text.empty()) {
        // As printed, not indented further: a line break more in the text of
        // one of its elements (a formula's) would change that text.
        out.append(printed.substr(line, grid_at - line)).append(rd_text);
        if (rd_text.back() != '\n') out.push_back('\n');
    }
    std::size_t at = line;
    for (const std::string& t : texts) {
        const std::size_t open = printed.find("<DataArray ", at), close = printed.find("/>", open);
        if (open == std::string_view::npos || close == std::string_view::npos)
            throw std::logic_error("write_vtu: an array's element is not where it was put");
        out.append(printed.substr(at, close - at)).append(">").append(t).append("</DataArray>");
        at = close + 2;
    }
    out.append(printed.substr(at));
    return out;
}

}  // namespace ready::vtu
