#include "ready/pattern.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "description/integer_text.hpp"
#include "description/plain_name.hpp"
#include "description/toml_writer.hpp"
#include "ready/vtk_arrays.hpp"
#include "sim/formula.hpp"
#include "sim/formula_names.hpp"

namespace ready {
namespace {

using description::printable;
using description::printable_short;
using tinyxml2::XMLElement;

// The formula scene's own [params] keys: a Ready parameter may not take one.
const char* const scene_keys[] = {"chemicals", "formula", "accuracy", "wrap",  "data_type", "block_x",
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

// "<formula number_of_chemicals>", "<param name=\"k\">": an element, and
// its attribute, as messages name them.
std::string element(const XMLElement* e, const char* attribute = nullptr) {
    return "<" + printable_short(e->Name(), 40) + (attribute ? std::string(" ") + attribute : "") + ">";
}

double number(const char* text, const std::string& what) {
    const std::string s = trimmed(text);
    double v = 0;
    const char* from = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(from, s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
        throw Refused(what + " is \"" + printable_short(s) + "\", not a finite number");
    return v;
}

double attribute(const XMLElement* e, const char* name, std::optional<double> fallback = std::nullopt) {
    const char* text = e->Attribute(name);
    if (!text) {
        if (fallback) return *fallback;
        throw Refused(element(e) + " has no " + name);
    }
    return number(text, element(e, name));
}

// An integer attribute from `low` to `high`, refused as written otherwise.
long long integer(const XMLElement* e, const char* name, long long fallback, long long low, long long high) {
    const char* text = e->Attribute(name);
    if (!text) return fallback;
    const std::string s = trimmed(text);
    if (const auto v = description::integer_text(s, low, high)) return *v;
    throw Refused(element(e, name) + " is \"" + printable_short(s) + "\", not an integer from " + std::to_string(low) +
                  " to " + std::to_string(high));
}

std::string text_attribute(const XMLElement* e, const char* name, const std::string& fallback) {
    const char* text = e->Attribute(name);
    return text ? trimmed(text) : fallback;
}

// Ready holds its parameters and overlay numbers as float: the value as
// the shortest decimal of that float. A value past float's range is kept
// as given, for the scene to refuse as it was written.
double as_float(double v) {
    if (std::fabs(v) > std::numeric_limits<float>::max()) return v;
    const float f = static_cast<float>(v);
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, f);
    double out = 0;
    std::from_chars(text, end, out);
    return out;
}

// Text a description may hold: as given when it is text, else escaped.
std::string as_text(const std::string& s, std::size_t most) {
    return description::is_text(s) && s.size() <= most ? s : printable_short(s, most);
}

const XMLElement* child(const XMLElement* e, const char* name) { return e ? e->FirstChildElement(name) : nullptr; }

const XMLElement* required(const XMLElement* e, const char* name) {
    const XMLElement* c = child(e, name);
    if (!c) throw Refused("no <" + std::string(name) + "> in " + element(e));
    return c;
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
    // tinyxml2's own message quotes the text it stopped at: its error's name and line only.
    if (p.xml.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
        throw Refused("not well-formed XML (line " + std::to_string(p.xml.ErrorLineNum()) + ": " +
                      tinyxml2::XMLDocument::ErrorIDToName(p.xml.ErrorID()) + ")");
}

// --- the file's parts, each read on its own --------------------------------

// The grid: <ImageData WholeExtent>, 2-D.
struct Grid {
    long long width = 0, height = 0;
};

Grid grid_of(const XMLElement* image) {
    std::array<long long, 6> extent{};
    std::istringstream s(text_attribute(image, "WholeExtent", ""));
    s.imbue(std::locale::classic());
    for (auto& v : extent)
        if (!(s >> v) || v < -1'000'000'000 || v > 1'000'000'000)
            throw Refused("<ImageData WholeExtent> is not six integers of at most 10^9");
    const long long nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1, nz = extent[5] - extent[4] + 1;
    if (nx < 1 || ny < 1 || nz < 1 || nx > 4096 || ny > 4096 || nz > 4096)
        throw Refused("its extent is " + std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) +
                      ": figgen runs grids up to 4096 x 4096");
    if (nz > 1)
        throw Refused("it is 3-D (" + std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) +
                      "): figgen runs 2-D patterns");
    if (ny == 1) throw Refused("it is 1-D (" + std::to_string(nx) + " cells): figgen runs 2-D patterns");
    return {nx, ny};
}

// How the file stores its arrays: <VTKFile byte_order header_type compressor>.
vtk::Encoding encoding_of(const XMLElement* vtk) {
    if (text_attribute(vtk, "byte_order", "LittleEndian") != "LittleEndian")
        throw Refused("<VTKFile byte_order> is \"" + printable_short(text_attribute(vtk, "byte_order", "")) +
                      "\": figgen reads LittleEndian");
    vtk::Encoding enc;
    const std::string header = text_attribute(vtk, "header_type", "UInt32");
    if (header == "UInt64") enc.header = 8;
    else if (header != "UInt32")
        throw Refused("<VTKFile header_type> is \"" + printable_short(header) + "\": figgen reads UInt32 and UInt64");
    const std::string compressor = text_attribute(vtk, "compressor", "");
    if (compressor == "vtkZLibDataCompressor") enc.compressed = true;
    else if (!compressor.empty())
        throw Refused("<VTKFile compressor> is \"" + printable_short(compressor) +
                      "\": figgen reads vtkZLibDataCompressor or none");
    return enc;
}

// The rule: <rule> and its <formula>.
struct Rule {
    int chemicals = 2, block_x = 4;
    std::string accuracy = "medium", code;
    bool wrap = true;
};

Rule rule_of(const XMLElement* rule) {
    const std::string kind = text_attribute(rule, "type", "");
    if (kind != "formula")
        throw Refused("its rule is type \"" + printable_short(kind) +
                      "\": figgen runs formula rules (type=\"formula\"), not full OpenCL kernels or Ready's inbuilt "
                      "rules");
    const XMLElement* formula = required(rule, "formula");
    Rule r;
    if (!formula->Attribute("number_of_chemicals")) throw Refused("<formula> has no number_of_chemicals");
    r.chemicals = static_cast<int>(integer(formula, "number_of_chemicals", 2, 1, sim::formula::max_chemicals));
    const long long block_x = integer(formula, "block_size_x", 4, 1, 4);
    if (block_x != 1 && block_x != 4)
        throw Refused("<formula block_size_x> is " + std::to_string(block_x) + ": figgen runs 1 or 4");
    r.block_x = static_cast<int>(block_x);
    if (integer(formula, "block_size_y", 1, 1, 64) != 1 || integer(formula, "block_size_z", 1, 1, 64) != 1)
        throw Refused("<formula block_size_y> and block_size_z are not 1: figgen runs blocks in x alone");
    r.accuracy = text_attribute(formula, "accuracy", "medium");
    if (r.accuracy != "low" && r.accuracy != "medium" && r.accuracy != "high")
        throw Refused("<formula accuracy> is \"" + printable_short(r.accuracy) + "\", not low, medium or high");
    r.code = dedented(trimmed(formula->GetText()));
    if (!description::is_text(r.code)) throw Refused("<formula> is not " + std::string(description::text_allowed));
    r.wrap = text_attribute(rule, "wrap", "1") == "1";
    return r;
}

// The names the formula reads, from its tree; none when it does not parse
// (the scene then refuses it, naming its line and column).
std::optional<std::set<std::string>> names_read(const std::string& code) {
    try {
        return sim::formula::names_read(sim::formula::parse(code));
    } catch (const sim::formula::FormulaError&) {
        return std::nullopt;
    }
}

toml::array point(const XMLElement* p) {
    return toml::array{as_float(attribute(p, "x")), as_float(attribute(p, "y")), as_float(attribute(p, "z"))};
}

// The nested point elements (point3D, any case) in order.
std::vector<const XMLElement*> points(const XMLElement* e, std::size_t count) {
    std::vector<const XMLElement*> out;
    for (const XMLElement* c = e->FirstChildElement(); c && out.size() <= count; c = c->NextSiblingElement())
        out.push_back(c);
    if (out.size() != count)
        throw Refused(element(e) + " needs " + std::to_string(count) + " nested point3D elements");
    return out;
}

// A fill's numbers (Ready's attribute, figgen's key, Ready's default if it
// has one) and its nested points, in order.
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
const FillKeys fill_keys[] = {
    {"constant", {{"value", "value", {}}}, {}},
    {"white_noise", {{"low", "low", {}}, {"high", "high", {}}}, {}},
    {"perlin_noise", {{"scale", "scale", 64}}, {}},
    {"linear_gradient", {{"val1", "val1", {}}, {"val2", "val2", {}}}, {"from", "to"}},
    {"radial_gradient", {{"val1", "val1", {}}, {"val2", "val2", {}}}, {"from", "to"}},
    {"gaussian", {{"height", "height", {}}, {"sigma", "sigma", {}}}, {"centre"}},
    {"sine", {{"phase", "phase", {}}, {"amplitude", "amplitude", {}}}, {"from", "to"}},
    {"other_chemical", {}, {}},
    {"parameter", {}, {}},
};

bool is_chemical(const std::string& name, int chemicals) {
    return name.size() == 1 && name[0] >= 'a' && name[0] < 'a' + chemicals;
}

void read_fill(const XMLElement* e, int chemicals, toml::table& t, std::set<std::string>& parameters_used) {
    const std::string name = e->Name();
    t.insert_or_assign("fill", name);
    for (const FillKeys& f : fill_keys) {
        if (name != f.fill) continue;
        for (const Number& n : f.numbers) t.insert(n.key, as_float(attribute(e, n.attribute, n.fallback)));
        if (!f.points.empty()) {
            const auto p = points(e, f.points.size());
            for (std::size_t k = 0; k < p.size(); ++k) t.insert(f.points[k], point(p[k]));
        }
    }
    if (name == "perlin_noise") t.insert("octaves", integer(e, "num_octaves", 8, 1, 16));
    if (name == "other_chemical") {
        const std::string other = text_attribute(e, "chemical", "");
        if (!is_chemical(other, chemicals))
            throw Refused("an overlay's <other_chemical chemical> is \"" + printable_short(other) +
                          "\", not one of the rule's");
        t.insert("other", other);
    } else if (name == "parameter") {
        const std::string p = text_attribute(e, "name", "");
        if (!description::is_text(p)) throw Refused("an overlay's <parameter name> is not " + std::string(description::text_allowed));
        t.insert("parameter", p);  // data: the scene checks it names one of the rule's parameters
        parameters_used.insert(p);
    }
}

// One shape of an overlay, or nothing when it can never apply to a 2-D grid.
std::optional<toml::table> read_shape(const XMLElement* e) {
    const std::string name = e->Name();
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
        if (z != 0 || x < 0 || y < 0 || x > 1e6 || y > 1e6) return std::nullopt;  // never a cell of a 2-D grid
        s.insert("at", toml::array{static_cast<std::int64_t>(x), static_cast<std::int64_t>(y)});
    }
    return s;
}

// One <overlay> as a table of params.initial, or nothing when it can never apply.
std::optional<toml::table> overlay(const XMLElement* o, int chemicals, std::set<std::string>& parameters_used) {
    toml::table t;
    const std::string chemical = text_attribute(o, "chemical", "");
    if (!is_chemical(chemical, chemicals))
        throw Refused("an <overlay chemical> is \"" + printable_short(chemical) + "\", not one of the rule's");
    t.insert("chemical", chemical);
    static const std::set<std::string> operations = {"overwrite", "add", "subtract", "multiply", "divide"};
    static const std::set<std::string> shape_names = {"everywhere", "rectangle", "circle", "pixel"};
    toml::array shapes;
    bool has_operation = false, has_fill = false, any_shape = false;
    for (const XMLElement* e = o->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const std::string name = e->Name();
        const bool fill = std::any_of(std::begin(fill_keys), std::end(fill_keys),
                                      [&](const FillKeys& f) { return name == f.fill; });
        if (operations.count(name)) {
            t.insert_or_assign("operation", name);
            has_operation = true;
        } else if (fill) {
            read_fill(e, chemicals, t, parameters_used);
            has_fill = true;
        } else if (shape_names.count(name)) {
            any_shape = true;
            if (auto s = read_shape(e)) shapes.push_back(std::move(*s));
        } else {
            throw Refused("an <overlay> holds " + element(e) + ", which Ready's overlays do not know");
        }
    }
    if (!has_operation || !has_fill || !any_shape)
        throw Refused("an <overlay> needs an operation, a fill and a shape, as Ready's do");
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
    if (!is_chemical(active, chemicals)) active = "a";
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

// Ready's description: its HTML tags out, its lines joined, no control characters.
std::string plain_text(const char* html) {
    std::string out;
    bool in_tag = false, space = false;
    for (const char* c = html ? html : ""; *c; ++c) {
        const auto u = static_cast<unsigned char>(*c);
        if (*c == '<') in_tag = true;
        else if (*c == '>') in_tag = false, space = true;
        else if (!in_tag) {
            if (std::isspace(u) || u < 0x20 || u == 0x7f) space = true;
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
    while (id.find("..") != std::string::npos) id.replace(id.find(".."), 2, "_.");
    if (id.size() > 100) id.resize(100);
    return id.empty() ? "pattern" : id;
}

// The stored arrays: a, b, ... in PointData, as Ready names them; or, as
// its older files have it, one array of a component per chemical.
struct StoredArrays {
    std::vector<const XMLElement*> named;  // a, b, ... in order
    const XMLElement* components = nullptr;
    bool float64 = false;
    bool found() const { return !named.empty() || components; }
};

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

std::string no_arrays(int chemicals) {
    return "it starts from its stored arrays, but holds neither arrays a, b, ... nor one of " +
           std::to_string(chemicals) + " components";
}

std::shared_ptr<description::StoredStart> start_shape(const StoredArrays& stored, const Grid& grid, int chemicals) {
    auto start = std::make_shared<description::StoredStart>();
    start->width = static_cast<int>(grid.width);
    start->height = static_cast<int>(grid.height);
    start->chemical_count = chemicals;
    start->float64 = stored.float64;
    return start;
}

std::shared_ptr<description::StoredStart> decode_start(const StoredArrays& stored, const ArrayReader& reader,
                                                       const Grid& grid, int chemicals) {
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

// [figure] and [animation] for `steps`: panels at 0, N/2 and N, sized to the grid.
void layout(toml::table& root, int steps, const Grid& grid) {
    std::vector<int> panels = {0, steps / 2, steps};
    panels.erase(std::unique(panels.begin(), panels.end()), panels.end());
    toml::array panel_list;
    for (int s : panels) panel_list.push_back(s);
    const int side = 300;
    const double aspect = static_cast<double>(grid.height) / static_cast<double>(grid.width);
    const int panel_height = static_cast<int>(std::clamp(0.72 * side * aspect, 60.0, 900.0));  // a colour bar beside each
    root.insert("figure", toml::table{{"panels", std::move(panel_list)},
                                      {"size", toml::array{side * static_cast<int>(panels.size()), panel_height + 70}}});
    if (steps > 0) {
        const int stride = std::max(1, steps / 100);
        const int film_height = static_cast<int>(std::clamp(480 * aspect, 64.0, 1440.0)) / 2 * 2 + 60;
        root.insert("animation", toml::table{{"steps", toml::array{0, steps}},
                                             {"stride", stride},
                                             {"fps", 25},
                                             {"size", toml::array{480, film_height}}});
    }
}

Pattern read(const std::string& text, const std::filesystem::path& file, const ReadOptions& options) {
    Parsed p;
    parse(text, p);
    const XMLElement* vtk = p.xml.FirstChildElement("VTKFile");
    if (!vtk) throw Refused("no <VTKFile>: not a VTK XML file");
    const std::string type = text_attribute(vtk, "type", "");
    if (type == "UnstructuredGrid")
        throw Refused("it is a mesh (<VTKFile type=\"UnstructuredGrid\">): figgen runs Ready's images (ImageData), "
                      "not meshes yet");
    if (type != "ImageData")
        throw Refused("<VTKFile type> is \"" + printable_short(type) + "\": figgen runs Ready's images (ImageData)");
    const XMLElement* rd = required(vtk, "RD");
    const XMLElement* rule_element = required(rd, "rule");
    const Rule rule = rule_of(rule_element);
    const vtk::Encoding enc = encoding_of(vtk);
    const XMLElement* image = required(vtk, "ImageData");
    const Grid grid = grid_of(image);
    const XMLElement* piece = required(image, "Piece");
    const StoredArrays stored = stored_arrays(piece, rule.chemicals);
    const XMLElement* generator = child(rd, "initial_pattern_generator");
    const bool apply = generator && text_attribute(generator, "apply_when_loading", "true") == "true";
    const bool zero_first = !generator || text_attribute(generator, "zero_first", "true") != "false";

    Pattern out;
    out.id = plain_id(file.stem().string());
    const std::string name = file.filename().string();
    const auto origin = [&](const std::string& key, const std::string& where) {
        out.origins[key] = printable_short(name, 120) + (where.empty() ? "" : " " + where);
    };
    // Ready starts from the stored arrays unless it regenerates the start
    // from zero: then its overlays (if it applies them) go on top.
    out.starts_from_arrays = !apply || !zero_first;
    if (out.starts_from_arrays && options.decode_arrays) {
        const ArrayReader reader{vtk, p.raw, enc, static_cast<std::uint64_t>(grid.width * grid.height)};
        out.start = decode_start(stored, reader, grid, rule.chemicals);
    } else if (out.starts_from_arrays) {
        if (!stored.found()) throw Refused(no_arrays(rule.chemicals));
        out.start = start_shape(stored, grid, rule.chemicals);  // its shape alone: nothing decoded
    }

    const int steps = options.steps.value_or(1000);
    toml::table root;
    root.insert("id", out.id);
    const std::string rule_name = text_attribute(rule_element, "name", "");
    root.insert("title", rule_name.empty() ? out.id : as_text(rule_name, 120));
    origin("description.title", "<rule name>");
    root.insert("source", "Ready's pattern " + printable_short(name, 120) + " (GollyGang/Ready)");
    root.insert("scene", "formula");
    root.insert("seed", 1);
    const std::string caption = plain_text(child(rd, "description") ? child(rd, "description")->GetText() : "");
    if (!caption.empty()) root.insert("caption", as_text(caption, 64 * 1024));
    origin("description.caption", "<description>");

    toml::table params;
    params.insert("chemicals", rule.chemicals);
    origin("params.chemicals", "<formula number_of_chemicals>");
    params.insert("formula", rule.code + "\n");
    origin("params.formula", "<formula>");
    params.insert("accuracy", rule.accuracy);
    origin("params.accuracy", "<formula accuracy>");
    params.insert("wrap", rule.wrap);
    origin("params.wrap", "<rule wrap>");
    params.insert("data_type", stored.float64 ? "double" : "float");
    origin("params.data_type", "<DataArray type>");
    params.insert("block_x", rule.block_x);
    origin("params.block_x", "<formula block_size_x>");
    params.insert("width", grid.width);
    params.insert("height", grid.height);
    origin("params.width", "<ImageData WholeExtent>");
    origin("params.height", "<ImageData WholeExtent>");
    params.insert("steps", steps);

    std::optional<std::set<std::string>> used = names_read(rule.code);
    if (used) used->insert({"timestep", "dx"});
    if (apply) {
        params.insert("zero_first", zero_first);
        origin("params.zero_first", "<initial_pattern_generator zero_first>");
        origin("params.initial", "<initial_pattern_generator>");
        toml::array initial;
        std::set<std::string> from_overlays;
        int n = 0;
        for (const XMLElement* o = generator->FirstChildElement("overlay"); o; o = o->NextSiblingElement("overlay")) {
            ++n;
            if (auto t = overlay(o, rule.chemicals, from_overlays)) {
                origin("params.initial[" + std::to_string(initial.size()) + "]",
                       "<overlay> " + std::to_string(n) + " of <initial_pattern_generator>");
                initial.push_back(std::move(*t));
            }
        }
        if (used) used->insert(from_overlays.begin(), from_overlays.end());
        if (!initial.empty()) params.insert("initial", std::move(initial));
    }
    std::vector<std::string> unused;
    for (const XMLElement* e = rule_element->FirstChildElement("param"); e; e = e->NextSiblingElement("param")) {
        const std::string param = text_attribute(e, "name", "");
        const std::string where = "<param name=\"" + printable_short(param, 40) + "\">";
        for (const char* k : scene_keys)
            if (param == k)
                throw Refused(where + " is a key of figgen's formula scene: a parameter may not take its name");
        if (const auto clash = sim::formula::parameter_name_clash(param, rule.chemicals))
            throw Refused(where + ": its name is " + *clash + "; " + sim::formula::parameter_name_allowed);
        const double v = as_float(number(e->GetText(), where));
        if (params.contains(param)) throw Refused(where + " is given twice");
        if (used && !used->count(param)) {
            unused.push_back(param);
            continue;
        }
        params.insert(param, v);
        origin("params." + param, where);
    }
    root.insert("params", std::move(params));
    root.insert("style", style_of(child(rd, "render_settings"), rule.chemicals));
    origin("style", "<render_settings>");
    layout(root, steps, grid);

    if (out.starts_from_arrays)
        out.notes.push_back("Ready starts this pattern from the arrays its file stores: `figgen render " +
                            printable_short(name, 120) +
                            "` starts from them; this description starts from zero, or from overlays you add as "
                            "params.initial.");
    if (!unused.empty()) {
        std::string note = "Parameters the formula does not use, left out:";
        for (const auto& u : unused) note += " " + u;
        out.notes.push_back(note);
    }
    out.description = std::move(root);
    return out;
}

std::optional<int> steps_override(const std::vector<std::string>& overrides) {
    std::optional<int> steps;
    for (const std::string& o : overrides) {
        for (const char* key : {"steps=", "params.steps="}) {
            const std::string k = key;
            if (o.compare(0, k.size(), k) == 0)
                if (auto v = description::integer_text(o.substr(k.size()), 0, 10'000'000)) steps = static_cast<int>(*v);
        }
    }
    return steps;
}

bool ends_with_nocase(const std::string& s, const char* suffix) {
    const std::size_t n = std::char_traits<char>::length(suffix);
    if (s.size() <= n) return false;
    for (std::size_t i = 0; i < n; ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i]) return false;
    return true;
}

}  // namespace

FileKind file_kind(const std::string& target) {
    if (ends_with_nocase(target, ".vti")) return FileKind::image;
    if (ends_with_nocase(target, ".vtu")) return FileKind::mesh;
    return FileKind::none;
}

Pattern read_pattern(const std::filesystem::path& file, const ReadOptions& options) {
    try {
        return read(read_file(file), file, options);
    } catch (const Refused& e) {
        throw description::FileError(printable(file.string()) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw description::FileError(printable(file.string()) + ": too large to read");
    }
}

Pattern read_pattern_text(const std::string& text, const std::filesystem::path& file, const ReadOptions& options) {
    try {
        if (text.size() > max_pattern_bytes) throw Refused("a pattern file is at most 256 MiB; this one is larger");
        return read(text, file, options);
    } catch (const Refused& e) {
        throw description::FileError(printable(file.string()) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw description::FileError(printable(file.string()) + ": too large to read");
    }
}

description::Description load_pattern(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                                      std::optional<std::uint64_t> seed, bool decode_arrays) {
    Pattern pattern = read_pattern(file, {steps_override(overrides), decode_arrays});
    description::Description d =
        description::description_from_table(std::move(pattern.description), file, std::move(pattern.origins), overrides, seed);
    d.stored_start = pattern.start;
    return d;
}

void decode_stored_start(description::Description& d) {
    if (!d.stored_start || d.stored_start->decoded()) return;
    const Pattern pattern = read_pattern(d.file, {std::nullopt, true});
    if (!pattern.start || pattern.start->width != d.stored_start->width ||
        pattern.start->height != d.stored_start->height)
        throw description::FileError(printable(d.file.string()) + ": changed while figgen read it");
    d.stored_start = pattern.start;
}

std::string converted_text(const Pattern& pattern, const std::filesystem::path& file) {
    std::ostringstream text;
    text << "# Converted by figgen from Ready's pattern " << printable_short(file.filename().string(), 120)
         << " (GollyGang/Ready).\n";
    for (const std::string& note : pattern.notes) text << "# " << printable(note) << "\n";
    text << "\n";
    const std::vector<std::string> rule = {"chemicals", "formula", "accuracy", "wrap", "data_type", "block_x",
                                           "width",     "height",  "steps",    "timestep", "dx"};
    description::write_toml(text, pattern.description, {"id", "title", "source", "scene", "seed", "caption"},
                            {{"params", rule}, {"style", {"show"}}, {"figure", {}}, {"animation", {}}});
    return text.str();
}

}  // namespace ready
