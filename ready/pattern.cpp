#include "ready/pattern.hpp"

#include "description/stored_mesh.hpp"
#include "ready/vtu.hpp"

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
#include "ready/reading.hpp"
#include "ready/vtk_arrays.hpp"
#include "sim/formula/rule.hpp"
#include "sim/formula/names.hpp"

namespace ready {
namespace {

using namespace reading;
using description::printable;
using description::printable_short;
using tinyxml2::XMLElement;

// The formula scene's own [params] keys: a Ready parameter may not take one.
const char* const scene_keys[] = {"chemicals", "formula", "accuracy", "wrap",  "data_type", "block_x",
                                  "ready_edges", "arithmetic", "width", "height", "depth", "steps", "zero_first",
                                  "initial", "integrator", "edges", "edge_value", "error"};


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

Grid grid_of(const XMLElement* image) {
    std::array<long long, 6> extent{};
    std::istringstream s(text_attribute(image, "WholeExtent", ""));
    s.imbue(std::locale::classic());
    for (auto& v : extent)
        if (!(s >> v) || v < -1'000'000'000 || v > 1'000'000'000)
            throw Refused("<ImageData WholeExtent> is not six integers of at most 10^9");
    const long long nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1, nz = extent[5] - extent[4] + 1;
    if (nx < 1 || ny < 1 || nz < 1 || nx > 4096 || ny > 4096 || nz > 4096 || nx * ny * nz > 4096LL * 4096LL)
        throw Refused("its extent is " + std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) +
                      ": figgen runs grids of up to 4096 cells a side and 4096 x 4096 cells in all");
    return {nx, ny, nz};
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
    bool ready_edges = true;  // false: a true torus, or each cell clamped
    bool inbuilt = false;     // Ready's inbuilt rule, written as the formula it computes
    bool kernel = false;      // a whole OpenCL kernel (code), run by figgen's own grammar
};

// Ready's inbuilt Gray-Scott rule (its GrayScottImageRD.cpp) as the formula
// it computes, in its order of operations: a seven-point Laplacian on every
// grid (on a 2-D or 1-D grid the missing neighbours are the cell itself, as
// Ready's indexing makes them), one cell a block, its edges a true torus or
// each cell clamped. Ready builds it with USE_SSE, so it adds nothing to
// keep numbers from becoming subnormal: the flush does that.
constexpr const char* inbuilt_gray_scott =
    "// Ready's inbuilt Gray-Scott rule (GrayScottImageRD.cpp), written as the formula it computes.\n"
    "float dda = a_s + a_n + a_w + a_e + a_d + a_u - 6*a;\n"
    "float ddb = b_s + b_n + b_w + b_e + b_d + b_u - 6*b;\n"
    "delta_a = D_a*dda - a*b*b + F*(1-a);\n"
    "delta_b = D_b*ddb + a*b*b - (F+k)*b;";

Rule rule_of(const XMLElement* rule) {
    const std::string kind = text_attribute(rule, "type", "");
    if (kind == "inbuilt") {
        const std::string name = text_attribute(rule, "name", "");
        if (name != "Gray-Scott")
            throw Refused("its rule is Ready's inbuilt \"" + printable_short(name) +
                          "\": figgen runs Ready's inbuilt Gray-Scott and formula rules");
        Rule r;
        r.block_x = 1;
        r.code = inbuilt_gray_scott;
        r.wrap = text_attribute(rule, "wrap", "1") == "1";
        r.ready_edges = false;
        r.inbuilt = true;
        return r;
    }
    if (kind == "kernel") {
        // Ready's FullKernelOpenCLImageRD: the kernel's text, its chemicals and blocks
        const XMLElement* kernel = required(rule, "kernel");
        Rule r;
        r.kernel = true;
        if (!kernel->Attribute("number_of_chemicals")) throw Refused("<kernel> has no number_of_chemicals");
        r.chemicals = static_cast<int>(integer(kernel, "number_of_chemicals", 1, 1, sim::formula::max_chemicals));
        const long long block_x = integer(kernel, "block_size_x", 1, 1, 4);
        if (block_x != 1 && block_x != 4)
            throw Refused("<kernel block_size_x> is " + std::to_string(block_x) + ": figgen runs 1 or 4");
        r.block_x = static_cast<int>(block_x);
        if (integer(kernel, "block_size_y", 1, 1, 64) != 1 || integer(kernel, "block_size_z", 1, 1, 64) != 1)
            throw Refused("<kernel block_size_y> and block_size_z are not 1: figgen runs blocks in x alone");
        r.code = dedented(trimmed(kernel->GetText() ? kernel->GetText() : ""));
        if (r.code.empty()) throw Refused("<kernel> is empty");
        if (!description::is_text(r.code)) throw Refused("<kernel> is not " + std::string(description::text_allowed));
        return r;
    }
    if (kind != "formula")
        throw Refused("its rule is type \"" + printable_short(kind) +
                      "\": figgen runs formula, kernel and Ready's inbuilt Gray-Scott rules");
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

// [figure] and [animation] for `steps`: panels at 0, N/2 and N, sized to
// the grid; a 1-D grid's space-time diagram and a 3-D grid's isosurface and
// slices on a page of their own shape.
void layout(toml::table& root, int steps, const Grid& grid) {
    std::vector<int> panels = {0, steps / 2, steps};
    panels.erase(std::unique(panels.begin(), panels.end()), panels.end());
    toml::array panel_list;
    for (int s : panels) panel_list.push_back(s);
    const bool line = grid.height == 1 && grid.depth == 1, solid = grid.depth > 1;
    const int side = 300;
    const double aspect = static_cast<double>(grid.height) / static_cast<double>(grid.width);
    const int panel_height = static_cast<int>(std::clamp(0.72 * side * aspect, 60.0, 900.0));  // a colour bar beside each
    const toml::array size = line    ? toml::array{900, 420}
                             : solid ? toml::array{960, 480}
                                     : toml::array{side * static_cast<int>(panels.size()), panel_height + 70};
    root.insert("figure", toml::table{{"panels", std::move(panel_list)}, {"size", size}});
    if (steps > 0) {
        const int stride = std::max(1, steps / 100);
        const int film_height = static_cast<int>(std::clamp(480 * aspect, 64.0, 1440.0)) / 2 * 2 + 60;
        const toml::array film = line ? toml::array{960, 420} : solid ? toml::array{640, 480} : toml::array{480, film_height};
        root.insert("animation", toml::table{{"steps", toml::array{0, steps}},
                                             {"stride", stride},
                                             {"fps", 25},
                                             {"size", film}});
    }
}

// What every pattern's description begins with: its id, title (the
// rule's name), source, scene, seed and caption (Ready's description).
template <class Origin>
toml::table description_head(const Pattern& out, const XMLElement* rd, const XMLElement* rule_element,
                             const std::string& name, const char* scene, const Origin& origin) {
    toml::table root;
    root.insert("id", out.id);
    const std::string rule_name = text_attribute(rule_element, "name", "");
    root.insert("title", rule_name.empty() ? out.id : as_text(rule_name, 120));
    origin("description.title", "<rule name>");
    root.insert("source", "Ready's pattern " + printable_short(name, 120) + " (GollyGang/Ready)");
    root.insert("scene", scene);
    root.insert("seed", 1);
    const std::string caption = plain_text(child(rd, "description") ? child(rd, "description")->GetText() : "");
    if (!caption.empty()) root.insert("caption", as_text(caption, 64 * 1024));
    origin("description.caption", "<description>");
    return root;
}

// A mesh (.vtu): Ready's MeshRD. Its cells and their chemicals are read
// whole (ready/vtu.hpp checks every count and index); the rule becomes
// the description of the mesh scene that runs it.
Pattern read_mesh(const std::string& text, const std::filesystem::path& file, const ReadOptions& options,
                  const XMLElement* vtk) {
    const XMLElement* rd = required(vtk, "RD");
    const XMLElement* rule_element = required(rd, "rule");
    const std::string kind = text_attribute(rule_element, "type", "");
    if (kind != "formula" && kind != "kernel")
        throw Refused("its rule is type \"" + printable_short(kind) +
                      "\": figgen runs formula and kernel rules on meshes");
    const XMLElement* code_element = required(rule_element, kind == "kernel" ? "kernel" : "formula");
    if (!code_element->Attribute("number_of_chemicals"))
        throw Refused("<" + kind + "> has no number_of_chemicals");
    const int chemicals =
        static_cast<int>(integer(code_element, "number_of_chemicals", 1, 1, sim::formula::max_chemicals));
    const std::string code = dedented(trimmed(code_element->GetText() ? code_element->GetText() : ""));
    if (code.empty()) throw Refused("<" + kind + "> is empty");
    if (!description::is_text(code)) throw Refused("<" + kind + "> is not " + std::string(description::text_allowed));
    const std::string neighbourhood = text_attribute(rule_element, "neighborhood_type", "vertex");
    if (neighbourhood != "vertex" && neighbourhood != "edge" && neighbourhood != "face")
        throw Refused("<rule neighborhood_type> is \"" + printable_short(neighbourhood) + "\": Ready's are vertex, edge and face");

    vtu::UnstructuredGrid grid;
    try {
        grid = vtu::read_vtu(text);
    } catch (const vtu::DataError& e) {
        throw Refused(e.what());
    }
    auto stored = std::make_shared<description::StoredMesh>();
    stored->chemical_count = chemicals;
    for (int c = 0; c < chemicals; ++c) {
        const std::string name = sim::formula::chemical_name(c);
        const vtu::CellArray* found = nullptr;
        for (const vtu::CellArray& a : grid.cell_data)
            if (a.name == name && a.components == 1) found = &a;
        if (!found)
            throw Refused("its <CellData> has no array \"" + name + "\" of one component: the rule has " +
                          std::to_string(chemicals) + " chemicals");
        stored->float64 = found->float64;
        stored->chemicals.push_back(found->values);
    }
    if (grid.mesh.cell_count() == 0) throw Refused("its mesh has no cells");
    stored->points = std::move(grid.mesh.points);
    stored->points_float64 = grid.points_float64;
    stored->offsets = std::move(grid.mesh.offsets);
    stored->point_ids = std::move(grid.mesh.point_ids);
    stored->types = std::move(grid.mesh.types);
    stored->faces = std::move(grid.mesh.faces);
    stored->face_offsets = std::move(grid.mesh.face_offsets);

    Pattern out;
    out.id = plain_id(file.stem().string());
    const std::string name = file.filename().string();
    const auto origin = [&](const std::string& key, const std::string& where) {
        out.origins[key] = printable_short(name, 120) + (where.empty() ? "" : " " + where);
    };
    const int steps = options.steps.value_or(1000);
    toml::table root = description_head(out, rd, rule_element, name, "mesh", origin);
    toml::table params;
    params.insert("chemicals", chemicals);
    origin("params.chemicals", "<" + kind + " number_of_chemicals>");
    params.insert(kind, code + "\n");
    origin("params." + kind, "<" + kind + ">");
    params.insert("data_type", stored->float64 ? "double" : "float");
    origin("params.data_type", "<DataArray type>");
    params.insert("neighborhood", neighbourhood);
    origin("params.neighborhood", "<rule neighborhood_type>");
    params.insert("steps", steps);
    // Ready regenerates a mesh's start from its overlays only where the file
    // says apply_when_loading="true" (RD_XMLUnstructuredGridReader)
    const XMLElement* generator = child(rd, "initial_pattern_generator");
    if (generator && text_attribute(generator, "apply_when_loading", "false") == "true") {
        params.insert("zero_first", text_attribute(generator, "zero_first", "true") != "false");
        origin("params.zero_first", "<initial_pattern_generator zero_first>");
        toml::array initial;
        std::set<std::string> from_overlays;
        int n = 0;
        for (const XMLElement* o = generator->FirstChildElement("overlay"); o; o = o->NextSiblingElement("overlay")) {
            ++n;
            if (auto t = overlay(o, chemicals, from_overlays)) {
                origin("params.initial[" + std::to_string(initial.size()) + "]",
                       "<overlay> " + std::to_string(n) + " of <initial_pattern_generator>");
                initial.push_back(std::move(*t));
            }
        }
        if (!initial.empty()) params.insert("initial", std::move(initial));
    }
    for (const XMLElement* e = rule_element->FirstChildElement("param"); e; e = e->NextSiblingElement("param")) {
        const std::string param = text_attribute(e, "name", "");
        const std::string where = "<param name=\"" + printable_short(param, 40) + "\">";
        if (kind == "kernel") throw Refused(where + ": a kernel rule's numbers are in its kernel");
        if (const auto clash = sim::formula::parameter_name_clash(param, chemicals))
            throw Refused(where + ": its name is " + *clash + "; " + sim::formula::parameter_name_allowed);
        if (params.contains(param)) throw Refused(where + " is given twice");
        params.insert(param, as_float(number(e->GetText(), where)));  // Ready holds a parameter as a float
        origin("params." + param, where);
    }
    root.insert("params", std::move(params));
    root.insert("style", style_of(child(rd, "render_settings"), chemicals));
    origin("style", "<render_settings>");
    std::vector<int> panels = {0, steps / 2, steps};
    panels.erase(std::unique(panels.begin(), panels.end()), panels.end());
    toml::array panel_list;
    for (int k : panels) panel_list.push_back(k);
    root.insert("figure", toml::table{{"panels", std::move(panel_list)},
                                      {"size", toml::array{330 * static_cast<int>(panels.size()) + 90, 400}}});
    if (steps > 0)
        root.insert("animation", toml::table{{"steps", toml::array{0, steps}},
                                             {"stride", std::max(1, steps / 100)},
                                             {"fps", 25},
                                             {"size", toml::array{560, 480}}});
    out.description = std::move(root);
    out.mesh = std::move(stored);
    (void)options;
    return out;
}

Pattern read(const std::string& text, const std::filesystem::path& file, const ReadOptions& options) {
    Parsed p;
    parse(text, p);
    const XMLElement* vtk = p.xml.FirstChildElement("VTKFile");
    if (!vtk) throw Refused("no <VTKFile>: not a VTK XML file");
    const std::string type = text_attribute(vtk, "type", "");
    if (type == "UnstructuredGrid") return read_mesh(text, file, options, vtk);
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
        out.start = decode_start(stored, vtk, p.raw, enc, grid, rule.chemicals);
    } else if (out.starts_from_arrays) {
        if (!stored.found()) throw Refused(no_arrays(rule.chemicals));
        out.start = start_shape(stored, grid, rule.chemicals);  // its shape alone: nothing decoded
    }

    const int steps = options.steps.value_or(1000);
    toml::table root = description_head(out, rd, rule_element, name, "formula", origin);

    toml::table params;
    params.insert("chemicals", rule.chemicals);
    const char* element = rule.kernel ? "<kernel" : "<formula";
    origin("params.chemicals", rule.inbuilt ? "<rule type=\"inbuilt\">" : element + std::string(" number_of_chemicals>"));
    if (rule.kernel) {
        params.insert("kernel", rule.code + "\n");
        origin("params.kernel", "<kernel>");
    } else {
        params.insert("formula", rule.code + "\n");
    }
    origin("params.formula", rule.inbuilt ? "<rule type=\"inbuilt\" name=\"Gray-Scott\">" : "<formula>");
    if (!rule.kernel) {
        params.insert("accuracy", rule.accuracy);
        origin("params.accuracy", rule.inbuilt ? "<rule type=\"inbuilt\">" : "<formula accuracy>");
        params.insert("wrap", rule.wrap);
        origin("params.wrap", "<rule wrap>");
    }
    params.insert("data_type", stored.float64 ? "double" : "float");
    origin("params.data_type", "<DataArray type>");
    if (!rule.kernel) {
        // Ready's formulas run through OpenCL, whose compiler contracts a * b + c;
        // its inbuilt rules are its own C++, built without contraction.
        params.insert("arithmetic", rule.inbuilt ? "plain" : "opencl");
        origin("params.arithmetic", rule.inbuilt ? "<rule type=\"inbuilt\">" : "<rule type=\"formula\">: OpenCL C");
    }
    params.insert("block_x", rule.block_x);
    origin("params.block_x", rule.inbuilt ? "<rule type=\"inbuilt\">" : element + std::string(" block_size_x>"));
    if (!rule.ready_edges) {
        params.insert("ready_edges", false);
        origin("params.ready_edges", "<rule type=\"inbuilt\">");
    }
    params.insert("width", grid.width);
    params.insert("height", grid.height);
    origin("params.width", "<ImageData WholeExtent>");
    origin("params.height", "<ImageData WholeExtent>");
    if (grid.depth > 1) {
        params.insert("depth", grid.depth);
        origin("params.depth", "<ImageData WholeExtent>");
    }
    params.insert("steps", steps);

    // a kernel reads no parameters: its numbers are in its text
    std::optional<std::set<std::string>> used =
        rule.kernel ? std::optional<std::set<std::string>>(std::set<std::string>{}) : names_read(rule.code);
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
    d.stored_mesh = pattern.mesh;
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
    const std::vector<std::string> rule = {"chemicals", "formula", "accuracy", "wrap",  "data_type", "block_x",
                                           "ready_edges", "arithmetic", "width", "height", "depth", "steps",
                                           "timestep", "dx"};
    description::write_toml(text, pattern.description, {"id", "title", "source", "scene", "seed", "caption"},
                            {{"params", rule}, {"style", {"show"}}, {"figure", {}}, {"animation", {}}});
    return text.str();
}

}  // namespace ready
