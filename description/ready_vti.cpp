#include "description/ready_vti.hpp"

#include <glib.h>
#include <tinyxml2.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "description/integer_text.hpp"
#include "description/plain_name.hpp"

namespace description {
namespace {

using tinyxml2::XMLElement;

// The formula scene's own [params] keys: a Ready parameter may not take one.
const char* const figgen_keys[] = {"chemicals", "formula", "accuracy", "wrap",  "data_type", "block_x",
                                   "ready_edges", "width", "height",   "steps", "zero_first", "initial"};

// What goes wrong in a file, before the file's name is put in front.
struct Refused : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string trimmed(const char* text) {
    std::string s = text ? text : "";
    const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
    s.erase(s.begin(), std::find_if_not(s.begin(), s.end(), space));
    s.erase(std::find_if_not(s.rbegin(), s.rend(), space).base(), s.end());
    return s;
}

// The lines after the first without the indentation they share (the XML's).
std::string dedented(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    std::size_t common = std::string::npos;
    for (std::size_t i = 1; i < lines.size(); ++i) {
        const std::size_t indent = lines[i].find_first_not_of(" \t");
        if (indent != std::string::npos) common = std::min(common, indent);
    }
    std::string out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const bool cut = i > 0 && common != std::string::npos && lines[i].size() >= common;
        if (i > 0) out += '\n';
        out.append(lines[i], cut ? common : 0, std::string::npos);
    }
    return out;
}

double number(const char* text, const std::string& what) {
    const std::string s = trimmed(text);
    double v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
        throw Refused(what + " is \"" + printable_short(s) + "\", not a finite number");
    return v;
}

double attribute(const XMLElement* e, const char* name, std::optional<double> fallback = std::nullopt) {
    const char* text = e->Attribute(name);
    if (!text) {
        if (fallback) return *fallback;
        throw Refused(std::string("<") + e->Name() + "> has no " + name);
    }
    return number(text, std::string("<") + e->Name() + " " + name + ">");
}

std::string text_attribute(const XMLElement* e, const char* name, const std::string& fallback) {
    const char* text = e->Attribute(name);
    return text ? trimmed(text) : fallback;
}

// Ready holds its parameters and overlay numbers as float: the value as
// the shortest decimal of that float.
double as_float(double v) {
    const float f = static_cast<float>(v);
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, f);
    double out = 0;
    std::from_chars(text, end, out);
    return out;
}

std::vector<std::uint8_t> base64(std::string_view text) {
    std::string clean;
    clean.reserve(text.size());
    for (char c : text)
        if (!std::isspace(static_cast<unsigned char>(c))) clean.push_back(c);
    if (clean.size() % 4 != 0) throw Refused("base64 data of " + std::to_string(clean.size()) + " characters, not a multiple of 4");
    for (char c : clean)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '='))
            throw Refused("base64 data holds a character outside base64");
    gsize length = 0;
    guchar* bytes = g_base64_decode(clean.c_str(), &length);
    std::vector<std::uint8_t> out(bytes, bytes + length);
    g_free(bytes);
    return out;
}

std::size_t base64_chars(std::uint64_t bytes) { return static_cast<std::size_t>((bytes + 2) / 3 * 4); }

// How the file stores its arrays.
struct Encoding {
    int header = 4;           // bytes of a header word: UInt32 or UInt64
    bool compressed = false;  // zlib blocks
};

std::uint64_t word(const std::uint8_t* p, int size) {
    if (size == 4) {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}

// The compressed blocks' header: count, block size, last block's size, each's compressed size.
struct Blocks {
    std::uint64_t count = 0, size = 0, last = 0;
    std::vector<std::uint64_t> compressed;
    std::uint64_t total_compressed() const {
        std::uint64_t t = 0;
        for (auto c : compressed) t += c;
        return t;
    }
};

Blocks read_blocks(const std::uint8_t* p, std::size_t available, int header, std::uint64_t expected) {
    Blocks b;
    if (available < 3u * header) throw Refused("a compressed array's header is cut short");
    b.count = word(p, header);
    b.size = word(p + header, header);
    b.last = word(p + 2 * header, header);
    if (b.count > (1u << 20) || b.size == 0 || b.size > (1u << 30) || b.last > b.size)
        throw Refused("a compressed array's header is not VTK's");
    const std::uint64_t bytes = b.count == 0 ? 0 : (b.count - 1) * b.size + (b.last ? b.last : b.size);
    if (bytes != expected)
        throw Refused("an array holds " + std::to_string(bytes) + " bytes, its extent needs " + std::to_string(expected));
    if (available < (3 + b.count) * header) throw Refused("a compressed array's header is cut short");
    for (std::uint64_t i = 0; i < b.count; ++i) b.compressed.push_back(word(p + (3 + i) * header, header));
    return b;
}

std::vector<std::uint8_t> inflate(const Blocks& b, const std::uint8_t* data, std::size_t available, std::uint64_t expected) {
    if (b.total_compressed() > available) throw Refused("a compressed array is cut short");
    std::vector<std::uint8_t> out(static_cast<std::size_t>(expected));
    std::size_t at = 0, from = 0;
    for (std::uint64_t i = 0; i < b.count; ++i) {
        const std::uint64_t want = i + 1 == b.count && b.last ? b.last : b.size;
        uLongf got = static_cast<uLongf>(want);
        if (uncompress(out.data() + at, &got, data + from, static_cast<uLong>(b.compressed[i])) != Z_OK || got != want)
            throw Refused("a compressed block does not inflate to its size (zlib)");
        at += want;
        from += b.compressed[i];
    }
    return out;
}

// An array's bytes from base64 text that starts at its header (inline
// binary, or appended base64 from its offset).
std::vector<std::uint8_t> from_base64(std::string_view spaced, const Encoding& e, std::uint64_t expected) {
    std::string kept;  // the text without the whitespace that VTK (or an editor) put in it
    kept.reserve(spaced.size());
    for (char c : spaced)
        if (!std::isspace(static_cast<unsigned char>(c))) kept.push_back(c);
    const std::string_view text = kept;
    if (!e.compressed) {
        const std::size_t head = base64_chars(e.header);
        if (text.size() < head) throw Refused("an array's header is cut short");
        const auto header = base64(text.substr(0, head));
        const std::uint64_t bytes = word(header.data(), e.header);
        if (bytes != expected)
            throw Refused("an array holds " + std::to_string(bytes) + " bytes, its extent needs " + std::to_string(expected));
        const std::size_t chars = base64_chars(e.header + bytes);
        if (text.size() < chars) throw Refused("an array is cut short");
        auto all = base64(text.substr(0, chars));
        return {all.begin() + e.header, all.begin() + e.header + static_cast<std::ptrdiff_t>(bytes)};
    }
    const std::size_t first = base64_chars(3u * e.header);
    if (text.size() < first) throw Refused("a compressed array's header is cut short");
    const auto start = base64(text.substr(0, first));
    const std::uint64_t count = word(start.data(), e.header);
    if (count > (1u << 20)) throw Refused("a compressed array's header is not VTK's");
    const std::size_t head = base64_chars((3 + count) * e.header);
    if (text.size() < head) throw Refused("a compressed array's header is cut short");
    const auto header = base64(text.substr(0, head));
    const Blocks b = read_blocks(header.data(), header.size(), e.header, expected);
    const std::size_t chars = base64_chars(b.total_compressed());
    if (text.size() < head + chars) throw Refused("a compressed array is cut short");
    const auto data = base64(text.substr(head, chars));
    return inflate(b, data.data(), data.size(), expected);
}

// From raw bytes that start at its header (appended raw).
std::vector<std::uint8_t> from_raw(std::string_view bytes, const Encoding& e, std::uint64_t expected) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data());
    if (!e.compressed) {
        if (bytes.size() < static_cast<std::size_t>(e.header)) throw Refused("an array's header is cut short");
        const std::uint64_t n = word(p, e.header);
        if (n != expected)
            throw Refused("an array holds " + std::to_string(n) + " bytes, its extent needs " + std::to_string(expected));
        if (bytes.size() - e.header < n) throw Refused("an array is cut short");
        return {p + e.header, p + e.header + n};
    }
    const Blocks b = read_blocks(p, bytes.size(), e.header, expected);
    const std::size_t head = (3 + b.count) * e.header;
    return inflate(b, p + head, bytes.size() - head, expected);
}

std::vector<double> values_of(const std::vector<std::uint8_t>& bytes, bool float64) {
    std::vector<double> out(bytes.size() / (float64 ? 8 : 4));
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (float64) {
            std::memcpy(&out[i], bytes.data() + 8 * i, 8);
        } else {
            float f;
            std::memcpy(&f, bytes.data() + 4 * i, 4);
            out[i] = f;
        }
    }
    return out;
}

// The parts of a file: its XML, and the raw appended bytes cut out of it.
struct Parsed {
    tinyxml2::XMLDocument xml;
    std::string raw;  // appended raw data, after its '_'
};

void parse(const std::string& text, Parsed& p) {
    std::string xml = text;
    const std::size_t tag = text.find("<AppendedData");
    if (tag != std::string::npos) {
        const std::size_t close = text.find('>', tag);
        if (close == std::string::npos) throw Refused("<AppendedData> is not closed");
        if (text.substr(tag, close - tag).find("\"raw\"") != std::string::npos) {
            const std::size_t mark = text.find('_', close);
            const std::size_t end = text.rfind("</AppendedData>");
            if (mark == std::string::npos || end == std::string::npos || end < mark)
                throw Refused("<AppendedData encoding=\"raw\"> has no data between '_' and </AppendedData>");
            p.raw = text.substr(mark + 1, end - mark - 1);
            xml = text.substr(0, mark) + text.substr(end);
        }
    }
    if (p.xml.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
        throw Refused(std::string("not XML: ") + printable_short(p.xml.ErrorStr() ? p.xml.ErrorStr() : "", 120));
}

const XMLElement* child(const XMLElement* e, const char* name) { return e ? e->FirstChildElement(name) : nullptr; }

const XMLElement* required(const XMLElement* e, const char* name, const std::string& in) {
    const XMLElement* c = child(e, name);
    if (!c) throw Refused("no <" + std::string(name) + "> in <" + in + ">");
    return c;
}

}  // namespace

std::set<std::string> formula_words(const std::string& code) {
    std::set<std::string> words;
    for (std::size_t i = 0; i < code.size();) {
        const auto name_char = [&](std::size_t k, bool first) {
            const unsigned char c = static_cast<unsigned char>(code[k]);
            return std::isalpha(c) || c == '_' || (!first && std::isdigit(c));
        };
        if (!name_char(i, true) || (i > 0 && name_char(i - 1, false))) {
            ++i;
            continue;
        }
        std::size_t end = i;
        while (end < code.size() && name_char(end, false)) ++end;
        words.insert(code.substr(i, end - i));
        i = end;
    }
    return words;
}

namespace {

toml::array point(const XMLElement* p) {
    return toml::array{as_float(attribute(p, "x")), as_float(attribute(p, "y")), as_float(attribute(p, "z"))};
}

// The nested point elements (point3D, any case) in order.
std::vector<const XMLElement*> points(const XMLElement* e, std::size_t count) {
    std::vector<const XMLElement*> out;
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) out.push_back(c);
    if (out.size() != count)
        throw Refused("<" + std::string(e->Name()) + "> needs " + std::to_string(count) + " nested point3D elements");
    return out;
}

// One <overlay> as a table of params.initial, or nothing when it can never apply.
std::optional<toml::table> overlay(const XMLElement* o, int chemicals, std::set<std::string>& parameters_used) {
    toml::table t;
    const std::string chemical = text_attribute(o, "chemical", "");
    if (chemical.size() != 1 || chemical[0] < 'a' || chemical[0] >= 'a' + chemicals)
        throw Refused("an overlay's chemical is \"" + printable_short(chemical) + "\", not one of the rule's");
    t.insert("chemical", chemical);
    static const std::set<std::string> operations = {"overwrite", "add", "subtract", "multiply", "divide"};
    static const std::set<std::string> fills = {"constant",        "white_noise",     "perlin_noise",
                                                "linear_gradient", "radial_gradient", "gaussian",
                                                "sine",            "other_chemical",  "parameter"};
    static const std::set<std::string> shape_names = {"everywhere", "rectangle", "circle", "pixel"};
    toml::array shapes;
    bool has_operation = false, has_fill = false, any_shape = false;
    for (const XMLElement* e = o->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string name = e->Name();
        if (operations.count(name)) {
            t.insert_or_assign("operation", name);
            has_operation = true;
        } else if (fills.count(name)) {
            has_fill = true;
            t.insert_or_assign("fill", name);
            // Each fill's numbers (Ready's attribute, figgen's key, Ready's
            // default if it has one) and its nested points, in order.
            struct Number {
                const char* attribute;
                const char* key;
                std::optional<double> fallback;
            };
            struct FillKeys {
                const char* fill;
                std::vector<Number> numbers;
                std::vector<const char*> points;
            };
            static const FillKeys fill_keys[] = {
                {"constant", {{"value", "value", {}}}, {}},
                {"white_noise", {{"low", "low", {}}, {"high", "high", {}}}, {}},
                {"perlin_noise", {{"scale", "scale", 64}}, {}},
                {"linear_gradient", {{"val1", "val1", {}}, {"val2", "val2", {}}}, {"from", "to"}},
                {"radial_gradient", {{"val1", "val1", {}}, {"val2", "val2", {}}}, {"from", "to"}},
                {"gaussian", {{"height", "height", {}}, {"sigma", "sigma", {}}}, {"centre"}},
                {"sine", {{"phase", "phase", {}}, {"amplitude", "amplitude", {}}}, {"from", "to"}},
            };
            for (const FillKeys& f : fill_keys) {
                if (name != f.fill) continue;
                for (const Number& n : f.numbers) t.insert(n.key, as_float(attribute(e, n.attribute, n.fallback)));
                if (!f.points.empty()) {
                    const auto p = points(e, f.points.size());
                    for (std::size_t k = 0; k < p.size(); ++k) t.insert(f.points[k], point(p[k]));
                }
            }
            if (name == "perlin_noise") t.insert("octaves", static_cast<std::int64_t>(attribute(e, "num_octaves", 8)));
            if (name == "other_chemical") {
                const std::string other = text_attribute(e, "chemical", "");
                if (other.size() != 1 || other[0] < 'a' || other[0] >= 'a' + chemicals)
                    throw Refused("an overlay's other_chemical is \"" + printable_short(other) + "\", not one of the rule's");
                t.insert("other", other);
            } else if (name == "parameter") {
                const std::string p = text_attribute(e, "name", "");
                t.insert("parameter", p);
                parameters_used.insert(p);
            }
        } else if (shape_names.count(name)) {
            any_shape = true;
            toml::table s{{"shape", name}};
            if (name == "rectangle") {
                const auto p = points(e, 2);
                s.insert("from", point(p[0]));
                s.insert("to", point(p[1]));
            } else if (name == "circle") {
                s.insert("radius", as_float(attribute(e, "radius")));
                s.insert("centre", point(points(e, 1)[0]));
            } else if (name == "pixel") {
                const double x = attribute(e, "x"), y = attribute(e, "y"), z = attribute(e, "z", 0);
                if (z != 0 || x < 0 || y < 0) continue;  // never a cell of a 2-D grid
                s.insert("at", toml::array{static_cast<std::int64_t>(x), static_cast<std::int64_t>(y)});
            }
            shapes.push_back(std::move(s));
        } else {
            throw Refused("an overlay holds <" + printable_short(name) + ">, which Ready's overlays do not know");
        }
    }
    if (!has_operation || !has_fill || !any_shape)
        throw Refused("an overlay needs an operation, a fill and a shape, as Ready's do");
    if (shapes.empty()) return std::nullopt;
    t.insert("shapes", std::move(shapes));
    return t;
}

std::string hex(double r, double g, double b) {
    char text[8];
    const auto c = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
    std::snprintf(text, sizeof text, "#%02x%02x%02x", c(r), c(g), c(b));
    return text;
}

// [style] from Ready's render_settings: the active chemical through
// Ready's colour map from low to high.
toml::table style_of(const XMLElement* rs, int chemicals) {
    const auto value = [&](const char* name) -> const XMLElement* { return child(rs, name); };
    std::string active = "a";
    if (const XMLElement* e = value("active_chemical")) active = text_attribute(e, "value", "a");
    if (active.size() != 1 || active[0] < 'a' || active[0] >= 'a' + chemicals) active = "a";
    double low = 0, high = 1;
    if (const XMLElement* e = value("low")) low = as_float(attribute(e, "value", 0));
    if (const XMLElement* e = value("high")) high = as_float(attribute(e, "value", 1));
    if (!(high > low)) high = low + 1;
    std::string map = "spectral";
    if (const XMLElement* e = value("colormap")) map = text_attribute(e, "value", map);
    bool bar = true;
    if (const XMLElement* e = value("show_color_scale")) bar = text_attribute(e, "value", "true") == "true";
    toml::table s{{"show", toml::array{active}}};
    const std::string p = active + "_";
    // Brewer's Spectral (9), red to blue, and Ready's terrain.
    static const std::vector<std::string> spectral = {"#d53e4f", "#f46d43", "#fdae61", "#fee08b", "#ffffbf",
                                                      "#e6f598", "#abdda4", "#66c2a5", "#3288bd"};
    static const std::vector<std::string> terrain = {"#333399", "#0099ff", "#00cc66", "#ffff99", "#805c54", "#ffffff"};
    std::vector<std::string> colours;
    std::string blend = "rgb";
    bool reverse = false;
    if (map == "HSV blend") {
        double r = 0, g = 0, b = 1, r2 = 1, g2 = 0, b2 = 0;
        if (const XMLElement* e = value("color_low")) r = attribute(e, "r", 0), g = attribute(e, "g", 0), b = attribute(e, "b", 1);
        if (const XMLElement* e = value("color_high")) r2 = attribute(e, "r", 1), g2 = attribute(e, "g", 0), b2 = attribute(e, "b", 0);
        colours = {hex(r, g, b), hex(r2, g2, b2)};
        blend = "hsv";
    } else if (map == "inferno" || map == "inferno reversed") {
        s.insert(p + "colormap", "inferno");
    } else if (map == "terrain" || map == "terrain reversed") {
        colours = terrain;
        reverse = map == "terrain reversed";
    } else {  // spectral, Ready's default: blue at low; "spectral reversed": red at low
        colours = spectral;
        reverse = map != "spectral reversed";
    }
    if (reverse) std::reverse(colours.begin(), colours.end());
    if (!colours.empty()) {
        toml::array list;
        for (const auto& c : colours) list.push_back(c);
        s.insert(p + "colours", std::move(list));
        s.insert(p + "blend", blend);
    }
    s.insert(p + "vmin", low);
    s.insert(p + "vmax", high);
    s.insert(p + "colour_bar", bar);
    s.insert(p + "sampling", "nearest");
    return s;
}

// Ready's description: its HTML tags out, its lines joined.
std::string plain_text(const char* html) {
    std::string out;
    bool in_tag = false, space = false;
    for (const char* c = html ? html : ""; *c; ++c) {
        if (*c == '<') in_tag = true;
        else if (*c == '>') in_tag = false, space = true;
        else if (!in_tag) {
            if (std::isspace(static_cast<unsigned char>(*c))) space = true;
            else {
                if (space && !out.empty()) out += ' ';
                space = false;
                out += *c;
            }
        }
    }
    return out;
}

std::string plain_id(const std::string& stem) {
    std::string id;
    for (char c : stem) id += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
    while (!id.empty() && id[0] == '.') id.erase(0, 1);
    if (id.size() > 100) id.resize(100);
    return id.empty() ? "pattern" : id;
}

std::string read_file(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw Refused("not a regular file");
    if (std::filesystem::file_size(file, ec) > max_pattern_bytes)
        throw Refused("a pattern file is at most 256 MiB; this one is larger");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Refused("cannot be read");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw Refused("cannot be read");
    return s.str();
}

// The file's arrays, decoded whichever way VTK wrote them.
struct Arrays {
    const XMLElement* vtk;
    const std::string& raw;  // appended raw data
    Encoding enc;
    std::uint64_t cells;

    // `array`'s values, `components` a cell; sets `float64` to its type.
    std::vector<double> read(const XMLElement* array, int components, bool& float64) const {
        const std::string name = printable_short(text_attribute(array, "Name", ""));
        const std::string t = text_attribute(array, "type", "");
        if (t != "Float32" && t != "Float64") throw Refused("array " + name + " is " + printable_short(t) + ": figgen reads Float32 and Float64");
        float64 = t == "Float64";
        const std::uint64_t count = cells * static_cast<std::uint64_t>(components);
        const std::uint64_t bytes = count * (float64 ? 8 : 4);
        const std::string format = text_attribute(array, "format", "ascii");
        std::vector<double> values;
        if (format == "ascii") {
            std::istringstream s(array->GetText() ? array->GetText() : "");
            s.imbue(std::locale::classic());
            double v;
            while (values.size() <= count && s >> v) values.push_back(float64 ? v : static_cast<float>(v));
            if (values.size() != count || !(s >> std::ws).eof())
                throw Refused("ascii array " + name + " does not hold " + std::to_string(count) + " numbers");
        } else if (format == "binary") {
            values = values_of(from_base64(array->GetText() ? array->GetText() : "", enc, bytes), float64);
        } else if (format == "appended") {
            const XMLElement* appended = child(vtk, "AppendedData");
            if (!appended) throw Refused("array " + name + " is appended, but there is no <AppendedData>");
            const double offset = attribute(array, "offset");
            if (offset < 0) throw Refused("array " + name + "'s offset is negative");
            const std::string encoding = text_attribute(appended, "encoding", "");
            if (encoding == "raw") {
                if (offset > static_cast<double>(raw.size())) throw Refused("array " + name + "'s offset is past the data");
                values = values_of(from_raw(std::string_view(raw).substr(static_cast<std::size_t>(offset)), enc, bytes), float64);
            } else if (encoding == "base64") {
                std::string_view text = appended->GetText() ? appended->GetText() : "";
                const std::size_t mark = text.find('_');
                if (mark == std::string_view::npos) throw Refused("<AppendedData> has no '_' before its data");
                text.remove_prefix(mark + 1);
                if (offset > static_cast<double>(text.size())) throw Refused("array " + name + "'s offset is past the data");
                values = values_of(from_base64(text.substr(static_cast<std::size_t>(offset)), enc, bytes), float64);
            } else {
                throw Refused("<AppendedData encoding> is " + printable_short(encoding) + ": figgen reads raw and base64");
            }
        } else {
            throw Refused("array " + name + "'s format is " + printable_short(format) + ": figgen reads ascii, binary and appended");
        }
        for (double v : values)
            if (!std::isfinite(v)) throw Refused("array " + name + " holds a value that is not a finite number");
        return values;
    }
};

// --- the description's text ----------------------------------------------

void write_value(std::ostream& out, const toml::node& v);

void write_number(std::ostream& out, double v) {
    char text[40];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, v);  // the shortest that reads back the same
    std::string s(text, end);
    if (s.find_first_of(".en") == std::string::npos) s += ".0";
    out << s;
}

void write_value(std::ostream& out, const toml::node& v) {
    if (const auto* s = v.as_string()) {
        out << *s;  // toml++ quotes and escapes it; a text of lines as a multi-line string
    } else if (const auto* f = v.as_floating_point()) {
        write_number(out, f->get());
    } else if (const auto* i = v.as_integer()) {
        out << i->get();
    } else if (const auto* b = v.as_boolean()) {
        out << (b->get() ? "true" : "false");
    } else if (const auto* a = v.as_array()) {
        out << "[";
        for (std::size_t k = 0; k < a->size(); ++k) {
            out << (k ? ", " : "");
            write_value(out, *a->get(k));
        }
        out << "]";
    } else if (const auto* t = v.as_table()) {
        out << "{";
        bool first = true;
        for (const auto& [key, value] : *t) {
            out << (first ? "" : ", ") << key.str() << " = ";
            write_value(out, value);
            first = false;
        }
        out << "}";
    }
}

// The keys of `t`: those of `first` in that order, then the others.
std::vector<std::string> ordered(const toml::table& t, const std::vector<std::string>& first) {
    std::vector<std::string> keys;
    for (const auto& k : first)
        if (t.contains(k)) keys.push_back(k);
    for (const auto& [k, v] : t)
        if (std::find(keys.begin(), keys.end(), std::string(k.str())) == keys.end()) keys.emplace_back(k.str());
    return keys;
}

void write_section(std::ostream& out, const std::string& name, const toml::table& t, const std::vector<std::string>& first) {
    std::vector<std::string> tables;  // arrays of tables, after the keys
    out << "\n[" << name << "]\n";
    for (const auto& key : ordered(t, first)) {
        const toml::node& v = *t.get(key);
        if (v.is_array_of_tables()) {
            tables.push_back(key);
            continue;
        }
        out << key << " = ";
        write_value(out, v);
        out << "\n";
    }
    for (const auto& key : tables)
        for (const toml::node& item : *t.get(key)->as_array()) {
            out << "\n[[" << name << "." << key << "]]\n";
            for (const auto& [k, v] : *item.as_table()) {
                out << k.str() << " = ";
                write_value(out, v);
                out << "\n";
            }
        }
}

// The description in the order a person reads it: who it is, the rule,
// the start, then how it is drawn.
void write_toml(std::ostream& out, const toml::table& root) {
    for (const auto& key : ordered(root, {"id", "title", "source", "scene", "seed", "caption"})) {
        const toml::node& v = *root.get(key);
        if (v.is_table()) continue;
        out << key << " = ";
        write_value(out, v);
        out << "\n";
    }
    const std::vector<std::string> rule = {"chemicals", "formula", "accuracy", "wrap", "data_type", "block_x",
                                           "width",     "height",  "steps",    "timestep", "dx"};
    for (const char* section : {"params", "style", "figure", "animation"})
        if (const toml::table* t = root[section].as_table())
            write_section(out, section, *t, std::string(section) == "params" ? rule : std::vector<std::string>{"show"});
}


ReadyPattern read_pattern(const std::filesystem::path& file, std::optional<int> steps_given) {
    Parsed p;
    parse(read_file(file), p);
    const XMLElement* vtk = p.xml.FirstChildElement("VTKFile");
    if (!vtk) throw Refused("no <VTKFile>: not a VTK XML file");
    const std::string type = text_attribute(vtk, "type", "");
    if (type != "ImageData")
        throw Refused("its data is " + printable_short(type) + ": figgen runs Ready's images (ImageData), not meshes");
    const XMLElement* rd = required(vtk, "RD", "VTKFile");
    const XMLElement* rule = required(rd, "rule", "RD");
    const std::string kind = text_attribute(rule, "type", "");
    if (kind != "formula")
        throw Refused("its rule is type \"" + printable_short(kind) +
                      "\": figgen runs formula rules (type=\"formula\"), not full OpenCL kernels or Ready's inbuilt rules");
    if (text_attribute(vtk, "byte_order", "LittleEndian") != "LittleEndian")
        throw Refused("byte_order is " + printable_short(text_attribute(vtk, "byte_order", "")) + ": figgen reads LittleEndian");
    Encoding enc;
    const std::string header = text_attribute(vtk, "header_type", "UInt32");
    if (header == "UInt64") enc.header = 8;
    else if (header != "UInt32") throw Refused("header_type is " + printable_short(header) + ": figgen reads UInt32 and UInt64");
    const std::string compressor = text_attribute(vtk, "compressor", "");
    if (compressor == "vtkZLibDataCompressor") enc.compressed = true;
    else if (!compressor.empty())
        throw Refused("compressor is " + printable_short(compressor) + ": figgen reads vtkZLibDataCompressor or none");

    // The grid.
    const XMLElement* image = required(vtk, "ImageData", "VTKFile");
    std::array<long long, 6> extent{};
    {
        std::istringstream s(text_attribute(image, "WholeExtent", ""));
        for (auto& v : extent)
            if (!(s >> v)) throw Refused("<ImageData WholeExtent> is not six integers");
    }
    const long long nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1, nz = extent[5] - extent[4] + 1;
    if (nx < 1 || ny < 1 || nz < 1 || nx > 4096 || ny > 4096 || nz > 4096)
        throw Refused("its extent is " + std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) +
                      ": figgen runs grids up to 4096 x 4096");
    if (nz > 1) throw Refused("it is 3-D (" + std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) + "): figgen runs 2-D patterns");
    if (ny == 1) throw Refused("it is 1-D (" + std::to_string(nx) + " cells): figgen runs 2-D patterns");

    const XMLElement* formula = required(rule, "formula", "rule");
    const int chemicals = static_cast<int>(attribute(formula, "number_of_chemicals"));
    if (chemicals < 1 || chemicals > 26) throw Refused("number_of_chemicals is " + std::to_string(chemicals) + ", not from 1 to 26");
    const int block_x = static_cast<int>(attribute(formula, "block_size_x", 4));
    if (block_x != 1 && block_x != 4) throw Refused("block_size_x is " + std::to_string(block_x) + ": figgen runs 1 or 4");
    if (attribute(formula, "block_size_y", 1) != 1 || attribute(formula, "block_size_z", 1) != 1)
        throw Refused("block_size_y and block_size_z are not 1: figgen runs blocks in x alone");
    const std::string accuracy = text_attribute(formula, "accuracy", "medium");
    if (accuracy != "low" && accuracy != "medium" && accuracy != "high")
        throw Refused("accuracy is \"" + printable_short(accuracy) + "\", not low, medium or high");
    const std::string code = dedented(trimmed(formula->GetText()));
    const bool wrap = text_attribute(rule, "wrap", "1") == "1";

    // The arrays: a, b, ... in PointData, as Ready names them; or, as its
    // older files have it, one array of a component per chemical.
    const XMLElement* piece = required(image, "Piece", "ImageData");
    const XMLElement* point_data = child(piece, "PointData");
    const std::uint64_t cells = static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny);
    const Arrays arrays{vtk, p.raw, enc, cells};
    auto start = std::make_shared<StoredStart>();
    start->width = static_cast<int>(nx);
    start->height = static_cast<int>(ny);
    std::vector<const XMLElement*> named, all;
    for (const XMLElement* a = child(point_data, "DataArray"); a; a = a->NextSiblingElement("DataArray")) all.push_back(a);
    for (int c = 0; c < chemicals; ++c)
        for (const XMLElement* a : all)
            if (text_attribute(a, "Name", "") == std::string(1, static_cast<char>('a' + c))) named.push_back(a);
    const bool by_name = static_cast<int>(named.size()) == chemicals && static_cast<int>(all.size()) == chemicals;
    const bool by_component = !by_name && all.size() == 1 && attribute(all[0], "NumberOfComponents", 1) == chemicals;
    // The number type is the arrays' (Ready's too), read from their type
    // whether or not the arrays themselves are needed.
    if (by_name || by_component) start->float64 = text_attribute(all[0], "type", "") == "Float64";
    // Ready starts from the stored arrays unless it regenerates the start
    // from zero: then its overlays (if it applies them) go on top. Only
    // then are they decoded, and never more than max_start_bytes of them.
    const XMLElement* generator = child(rd, "initial_pattern_generator");
    const bool apply = generator && text_attribute(generator, "apply_when_loading", "true") == "true";
    const bool zero_first = !generator || text_attribute(generator, "zero_first", "true") != "false";
    if (!apply || !zero_first) {
        const double bytes = 8.0 * static_cast<double>(cells) * chemicals;
        if (bytes > static_cast<double>(max_start_bytes))
            throw Refused("its stored arrays would take " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                          " MiB as doubles: figgen reads at most " + std::to_string(max_start_bytes >> 20) +
                          " MiB of a pattern's arrays");
        if (!by_name && !by_component)
            throw Refused("it starts from its stored arrays, but holds neither arrays a, b, ... nor one of " +
                          std::to_string(chemicals) + " components");
        if (by_name) {
            for (const XMLElement* a : named) start->chemicals.push_back(arrays.read(a, 1, start->float64));
        } else {
            const std::vector<double> v = arrays.read(all[0], chemicals, start->float64);
            start->chemicals.assign(static_cast<std::size_t>(chemicals), std::vector<double>(cells));
            for (std::uint64_t i = 0; i < cells; ++i)
                for (int c = 0; c < chemicals; ++c) start->chemicals[static_cast<std::size_t>(c)][i] = v[i * chemicals + c];
        }
    }

    // The description.
    ReadyPattern out;
    out.id = plain_id(file.stem().string());
    const std::string rule_name = text_attribute(rule, "name", out.id);
    const int steps = steps_given.value_or(1000);
    toml::table root;
    root.insert("id", out.id);
    root.insert("title", rule_name.empty() ? out.id : printable_short(rule_name, 120));
    root.insert("source", "Ready's pattern " + printable_short(file.filename().string(), 120) + " (GollyGang/Ready)");
    root.insert("scene", "formula");
    root.insert("seed", 1);
    const std::string caption = plain_text(child(rd, "description") ? child(rd, "description")->GetText() : "");
    if (!caption.empty()) root.insert("caption", caption);

    toml::table params;
    params.insert("chemicals", chemicals);
    params.insert("formula", code + "\n");
    params.insert("accuracy", accuracy);
    params.insert("wrap", wrap);
    params.insert("data_type", start->float64 ? "double" : "float");
    params.insert("block_x", block_x);
    params.insert("width", nx);
    params.insert("height", ny);
    params.insert("steps", steps);

    std::set<std::string> used = formula_words(code);
    used.insert("timestep");
    used.insert("dx");
    if (!start->chemicals.empty()) out.start = start;
    if (apply) {
        params.insert("zero_first", zero_first);
        toml::array initial;
        for (const XMLElement* o = generator->FirstChildElement("overlay"); o; o = o->NextSiblingElement("overlay"))
            if (auto t = overlay(o, chemicals, used)) initial.push_back(std::move(*t));
        if (!initial.empty()) params.insert("initial", std::move(initial));
    }
    std::vector<std::string> unused;
    for (const XMLElement* e = rule->FirstChildElement("param"); e; e = e->NextSiblingElement("param")) {
        const std::string name = text_attribute(e, "name", "");
        const double v = as_float(number(e->GetText(), "parameter " + printable_short(name)));
        for (const char* k : figgen_keys)
            if (name == k) throw Refused("a parameter is named " + name + ", a key of figgen's formula scene: rename it");
        if (!used.count(name)) {
            unused.push_back(name);
            continue;
        }
        if (params.contains(name)) throw Refused("parameter " + printable_short(name) + " is given twice");
        params.insert(name, v);
    }
    root.insert("params", std::move(params));
    root.insert("style", style_of(child(rd, "render_settings"), chemicals));

    std::vector<int> panels = {0, steps / 2, steps};
    panels.erase(std::unique(panels.begin(), panels.end()), panels.end());
    toml::array panel_list;
    for (int s : panels) panel_list.push_back(s);
    const int side = 300;
    const double aspect = static_cast<double>(ny) / static_cast<double>(nx);
    const int panel_height = static_cast<int>(std::clamp(0.72 * side * aspect, 60.0, 900.0));  // a colour bar beside each
    root.insert("figure", toml::table{{"panels", std::move(panel_list)},
                                      {"size", toml::array{side * static_cast<int>(panels.size()), panel_height + 70}}});
    if (steps > 0) {
        const int stride = std::max(1, steps / 100);
        root.insert("animation", toml::table{{"steps", toml::array{0, steps}},
                                             {"stride", stride},
                                             {"fps", 25},
                                             {"size", toml::array{480, static_cast<int>(std::clamp(480 * aspect, 64.0, 1440.0)) / 2 * 2 + 60}}});
    }

    std::ostringstream text;
    text << "# Converted by figgen from Ready's pattern " << printable_short(file.filename().string(), 120)
         << " (GollyGang/Ready).\n";
    if (out.start)
        text << "# Ready starts this pattern from the arrays its file stores:\n"
                "# `figgen render " << printable_short(file.filename().string(), 120)
             << "` starts from them; this description starts from zero, or from overlays you add as params.initial.\n";
    if (!unused.empty()) {
        text << "# Parameters the formula does not use, left out:";
        for (const auto& u : unused) text << " " << printable_short(u);
        text << "\n";
    }
    text << "\n";
    write_toml(text, root);
    out.toml = text.str();
    return out;
}

std::optional<int> steps_override(const std::vector<std::string>& overrides) {
    std::optional<int> steps;
    for (const std::string& o : overrides) {
        for (const char* key : {"steps=", "params.steps="}) {
            const std::string k = key;
            if (o.compare(0, k.size(), k) == 0)
                if (auto v = integer_text(o.substr(k.size()), 0, 10'000'000)) steps = static_cast<int>(*v);
        }
    }
    return steps;
}

// --- writing ------------------------------------------------------------

std::string encoded_array(const std::vector<double>& values, bool float64) {
    std::vector<std::uint8_t> bytes(values.size() * (float64 ? 8 : 4));
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (float64) {
            std::memcpy(bytes.data() + 8 * i, &values[i], 8);
        } else {
            const float f = static_cast<float>(values[i]);
            std::memcpy(bytes.data() + 4 * i, &f, 4);
        }
    }
    const std::uint64_t block = 32768;
    const std::uint64_t count = (bytes.size() + block - 1) / block;
    // VTK's header: the blocks, their size, the last one's when it is shorter (else 0), each compressed size.
    std::vector<std::uint64_t> header = {count, block, bytes.size() % block};
    std::vector<std::uint8_t> data;
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::size_t from = static_cast<std::size_t>(i * block);
        const std::size_t n = std::min<std::size_t>(block, bytes.size() - from);
        uLongf size = compressBound(static_cast<uLong>(n));
        std::vector<std::uint8_t> out(size);
        if (compress2(out.data(), &size, bytes.data() + from, static_cast<uLong>(n), 5) != Z_OK)
            throw std::runtime_error("zlib could not compress an array");
        header.push_back(size);
        data.insert(data.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(size));
    }
    const auto encode = [](const void* p, std::size_t n) {
        gchar* text = g_base64_encode(static_cast<const guchar*>(p), n);
        std::string s(text);
        g_free(text);
        return s;
    };
    return encode(header.data(), header.size() * 8) + encode(data.data(), data.size());
}

}  // namespace

bool is_ready_pattern(const std::string& target) {
    return target.size() > 4 && target.compare(target.size() - 4, 4, ".vti") == 0;
}

ReadyPattern read_ready_pattern(const std::filesystem::path& file, std::optional<int> steps) {
    try {
        return read_pattern(file, steps);
    } catch (const Refused& e) {
        throw UsageError(printable(file.string()) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw UsageError(printable(file.string()) + ": too large to read");
    }
}

Description load_ready_pattern(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                               std::optional<std::uint64_t> seed) {
    const ReadyPattern pattern = read_ready_pattern(file, steps_override(overrides));
    Description d = parse_description(pattern.toml, file, overrides, seed);
    // Lines of the converted text mean nothing in the .vti: a key's origin
    // is the file itself, or the --set that gave it.
    for (auto it = d.origins.begin(); it != d.origins.end();)
        it = it->second.rfind("--set", 0) == 0 ? std::next(it) : d.origins.erase(it);
    d.stored_start = pattern.start;
    return d;
}

std::string ready_vti(const ReadyState& s) {
    tinyxml2::XMLDocument doc;
    tinyxml2::XMLElement* vtk = doc.NewElement("VTKFile");
    doc.InsertEndChild(doc.NewDeclaration());
    doc.InsertEndChild(vtk);
    vtk->SetAttribute("type", "ImageData");
    vtk->SetAttribute("version", "1.0");
    vtk->SetAttribute("byte_order", "LittleEndian");
    vtk->SetAttribute("header_type", "UInt64");
    vtk->SetAttribute("compressor", "vtkZLibDataCompressor");
    XMLElement* rd = vtk->InsertNewChildElement("RD");
    rd->SetAttribute("format_version", 6);
    rd->InsertNewChildElement("description")->SetText(s.description.c_str());
    XMLElement* rule = rd->InsertNewChildElement("rule");
    rule->SetAttribute("name", s.rule_name.c_str());
    rule->SetAttribute("type", "formula");
    rule->SetAttribute("wrap", s.wrap ? 1 : 0);
    rule->SetAttribute("neighborhood_type", "vertex");
    for (const auto& [name, value] : s.parameters) {
        XMLElement* p = rule->InsertNewChildElement("param");
        p->SetAttribute("name", name.c_str());
        char text[40];
        std::snprintf(text, sizeof text, "%.9g", value);
        p->SetText(text);
    }
    XMLElement* f = rule->InsertNewChildElement("formula");
    f->SetAttribute("number_of_chemicals", static_cast<int>(s.chemicals.size()));
    f->SetAttribute("block_size_x", s.block_x);
    f->SetAttribute("block_size_y", 1);
    f->SetAttribute("block_size_z", 1);
    f->SetAttribute("accuracy", s.accuracy.c_str());
    f->SetText(s.formula.c_str());
    rd->InsertNewChildElement("initial_pattern_generator")->SetAttribute("apply_when_loading", "false");
    XMLElement* rs = rd->InsertNewChildElement("render_settings");
    rs->InsertNewChildElement("active_chemical")->SetAttribute("value", s.active_chemical.c_str());
    if (s.low) rs->InsertNewChildElement("low")->SetAttribute("value", *s.low);
    if (s.high) rs->InsertNewChildElement("high")->SetAttribute("value", *s.high);
    XMLElement* image = vtk->InsertNewChildElement("ImageData");
    const std::string extent = "0 " + std::to_string(s.width - 1) + " 0 " + std::to_string(s.height - 1) + " 0 0";
    image->SetAttribute("WholeExtent", extent.c_str());
    image->SetAttribute("Origin", "0 0 0");
    image->SetAttribute("Spacing", "1 1 1");
    XMLElement* piece = image->InsertNewChildElement("Piece");
    piece->SetAttribute("Extent", extent.c_str());
    XMLElement* point_data = piece->InsertNewChildElement("PointData");
    for (std::size_t c = 0; c < s.chemicals.size(); ++c) {
        const auto& v = s.chemicals[c];
        XMLElement* a = point_data->InsertNewChildElement("DataArray");
        a->SetAttribute("type", s.float64 ? "Float64" : "Float32");
        a->SetAttribute("Name", std::string(1, static_cast<char>('a' + c)).c_str());
        a->SetAttribute("format", "binary");
        if (!v.empty()) {
            const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
            a->SetAttribute("RangeMin", *lo);
            a->SetAttribute("RangeMax", *hi);
        }
        a->SetText(encoded_array(v, s.float64).c_str());
    }
    piece->InsertNewChildElement("CellData");
    tinyxml2::XMLPrinter printer;
    doc.Print(&printer);
    return std::string(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
}

}  // namespace description
