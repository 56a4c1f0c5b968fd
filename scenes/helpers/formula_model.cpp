// What the formula scenes share (scenes/formula.cpp, formula_atlas.cpp):
// a formula model read from [params] and checked before anything runs.
#include "scenes/helpers/formula_model.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "description/stored_start.hpp"
#include "sim/formula/chain_kernels.hpp"
#include "sim/formula/names.hpp"
#include "sim/formula/program.hpp"
#include "sim/random.hpp"

namespace scenes {

namespace formula = sim::formula;

namespace {

bool is_key(const std::vector<Key>& keys, const std::string& name) {
    return std::any_of(keys.begin(), keys.end(), [&](const Key& k) { return k.name == name; });
}

// A point [x, y] or [x, y, z], fractions of the grid; z is the
// default's when not given.
std::array<double, 3> point(Settings& s, const std::string& key, std::array<double, 3> fallback) {
    const std::vector<double> v = s.numbers(key, {fallback[0], fallback[1]});
    if (v.size() < 2 || v.size() > 3) s.refuse(key, "[x, y] or [x, y, z]: fractions of the grid");
    for (double x : v)
        if (!std::isfinite(x) || std::fabs(x) > 1e6) s.refuse(key, "finite numbers, fractions of the grid");
    return {v[0], v[1], v.size() > 2 ? v[2] : fallback[2]};
}

// A point key read into `member`, with its default.
template <class T>
void point_key(Schema<T>& schema, const std::string& name, std::array<double, 3> T::*member,
               const std::string& meaning) {
    schema.key(
        {name, meaning, "a list of numbers", "[x, y] or [x, y, z], fractions of the grid"},
        [member](Settings& s, const std::string& key, T& v) { v.*member = point(s, key, v.*member); },
        [member](const T& d) {
            const auto& p = d.*member;
            return p[2] != 0 ? nlohmann::json({p[0], p[1], p[2]}) : nlohmann::json({p[0], p[1]});
        });
}

// One shape of an overlay: where it applies. Every key is read and
// checked, whichever the shape uses.
struct ShapeValues {
    formula::Shape shape;
    // A rectangle given [x, y] corners spans every plane of a 3-D grid.
    std::array<double, 3> centre{0.5, 0.5, 0}, from{0, 0, 0}, to{1, 1, 1};
    std::vector<long long> at{0, 0};
};

const Schema<ShapeValues> shape_schema = [] {
    using S = ShapeValues;
    Schema<S> s;
    Schema<formula::Shape> kind;
    kind.choice("shape", &formula::Shape::kind, formula::shape_names(), "where the overlay applies");
    s.part(kind, &S::shape);
    point_key(s, "from", &S::from, "rectangle: [x, y] or [x, y, z], its lower corner, a fraction of the grid");
    point_key(s, "to", &S::to, "rectangle: [x, y] or [x, y, z], its upper corner, a fraction of the grid");
    point_key(s, "centre", &S::centre, "circle (a sphere in 3-D): [x, y] or [x, y, z], a fraction of the grid");
    s.key(
        {"radius", "circle: a fraction of the grid's larger side", "a number", numbers_allowed(0, 1e6), 0.1},
        [](Settings& section, const std::string& key, S& v) { v.shape.radius = section.number_in(key, 0.1, 0, 1e6); });
    s.key(
        {"at", "pixel: [x, y] or [x, y, z], the cell", "a list of integers", "[x, y] or [x, y, z]: a cell of the grid"},
        [](Settings& section, const std::string& key, S& v) {
            v.at = section.integers(key, v.at);
            if (v.at.size() < 2 || v.at.size() > 3 ||
                std::any_of(v.at.begin(), v.at.end(), [](long long c) { return c < 0 || c > 100000; }))
                section.refuse(key, "[x, y] or [x, y, z]: a cell of the grid");
        },
        [](const S& d) { return nlohmann::json(d.at); });
    s.check([](Settings&, const std::string&, S& v) {
        v.shape.a = v.shape.kind == formula::Shape::Kind::circle ? v.centre : v.from;
        v.shape.b = v.to;
        v.shape.pixel = {static_cast<int>(v.at[0]), static_cast<int>(v.at[1]),
                         v.at.size() > 2 ? static_cast<int>(v.at[2]) : 0};
    });
    return s;
}();

// One of Ready's overlays: the chemical it changes, how, with what fill,
// where. Read over a rule already compiled: its chemicals and parameters
// bound the overlay's.
struct OverlayValues {
    formula::Overlay overlay;
    std::array<double, 3> centre{0.5, 0.5, 0}, from{0, 0, 0}, to{1, 1, 0};
    std::string where;                    // "params.initial[2]", for its shapes' sections
    const formula::Rule* rule = nullptr;  // the rule it starts
};

const Schema<OverlayValues> overlay_schema = [] {
    using O = OverlayValues;
    using F = formula::Fill;
    const double big = 1e12;
    Schema<F> fill;
    fill.choice("fill", &F::kind, formula::fill_names(), "what the overlay puts there (Ready's fills)");
    fill.number("value", &F::value, "constant: the value", -big, big);
    fill.number("low", &F::low, "white_noise: the least value", -big, big);
    fill.number("high", &F::high, "white_noise: the most value", -big, big);
    fill.number("scale", &F::scale, "perlin_noise: cells a feature", 1e-6, big);
    fill.count("octaves", &F::octaves, "perlin_noise: octaves", 1, 16);
    fill.number("val1", &F::val1, "linear_gradient, radial_gradient: the value at `from`", -big, big);
    fill.number("val2", &F::val2, "linear_gradient, radial_gradient: the value at `to`", -big, big);
    fill.number("height", &F::height, "gaussian: its height", -big, big);
    fill.number("sigma", &F::sigma, "gaussian: its width, a fraction of the grid's larger side", 1e-9, big);
    fill.number("phase", &F::phase, "sine: its phase, radians", -big, big);
    fill.number("amplitude", &F::amplitude, "sine: its amplitude", -big, big);

    Schema<O> s;
    s.key({"chemical", "the chemical it changes: \"a\", \"b\", ...", "text", "a chemical of the rule", "a"},
          [](Settings& section, const std::string& key, O& v) {
              v.overlay.chemical = chemical_index(section, key, section.text(key, "a"), v.rule->chemicals);
          });
    Schema<formula::Overlay> how;
    how.choice("operation", &formula::Overlay::operation, formula::operation_names(),
               "how the fill meets what the cells hold");
    s.part(how, &O::overlay);
    s.part_at(
        fill, [](auto& v) -> auto& { return v.overlay.fill; });
    point_key(s, "from", &O::from, "gradients and sine: [x, y], a fraction of the grid");
    point_key(s, "to", &O::to, "gradients and sine: [x, y], a fraction of the grid");
    point_key(s, "centre", &O::centre, "gaussian: [x, y], a fraction of the grid");
    s.key({"other", "other_chemical: the chemical copied", "text", "a chemical of the rule", "a"},
          [](Settings& section, const std::string& key, O& v) {
              v.overlay.fill.chemical = chemical_index(section, key, section.text(key, "a"), v.rule->chemicals);
          });
    s.key({"parameter", "parameter: the rule's parameter copied", "text", "the name of one of the rule's parameters",
           "timestep"},
          [](Settings& section, const std::string& key, O& v) {
              // checked where it is read: a kernel rule has no parameters, not even timestep
              if (!section.has(key) && v.overlay.fill.kind != formula::Fill::Kind::parameter) return;
              v.overlay.fill.parameter = section.text(key, "timestep");
              bool found = false;
              for (const auto& [name, value] : v.rule->parameters) found |= name == v.overlay.fill.parameter;
              if (!found) section.refuse(key, "the name of one of the rule's parameters");
          });
    s.key({"shapes", "where: [{shape = \"everywhere\"}], circle {centre, radius}, rectangle {from, to}, pixel {at}",
           "a list of tables", "one shape at least"},
          [](Settings& section, const std::string& key, O& v) {
              const auto shapes = section.tables(key);
              if (shapes.empty()) section.refuse(key, "[]", "one shape at least, e.g. [{shape = \"everywhere\"}]");
              for (std::size_t j = 0; j < shapes.size(); ++j) {
                  Settings sh(v.where + "." + key + "[" + std::to_string(j) + "]", shapes[j], shape_schema.keys());
                  v.overlay.shapes.push_back(shape_schema.read(sh).shape);
              }
          });
    s.check([](Settings&, const std::string&, O& v) {
        v.overlay.fill.p1 = v.overlay.fill.kind == formula::Fill::Kind::gaussian ? v.centre : v.from;
        v.overlay.fill.p2 = v.to;
    });
    return s;
}();

// figgen's own edges (formula::Edges): `edges`, one word for every side or
// a table of sides, and `edge_value`, the dirichlet sides' values.
const std::vector<std::pair<std::string, formula::Edge>> edge_words = {
    {"periodic", formula::Edge::periodic}, {"neumann", formula::Edge::neumann}, {"dirichlet", formula::Edge::dirichlet}};
const std::string edges_allowed = "\"periodic\", \"neumann\" or \"dirichlet\"";

std::vector<Key> side_keys(const std::string& meaning, const std::string& type, const std::string& allowed) {
    std::vector<Key> keys;
    for (int side = 0; side < 6; ++side) keys.push_back({formula::side_name(side), meaning, type, allowed});
    return keys;
}

formula::Edge edge_word(Settings& s, const std::string& key) {
    const std::string given = s.text(key, "periodic");
    for (const auto& [word, edge] : edge_words)
        if (word == given) return edge;
    s.refuse(key, edges_allowed);
}

void read_edges(Settings& s, const std::string& key, formula::Rule& r) {
    const toml::node* node = s.node(key);
    if (!node) return;
    if (const toml::table* table = node->as_table()) {
        Settings sides(s.section() + "." + key, *table,
                       side_keys("this side's edge; a side not given is periodic", "text", edges_allowed));
        formula::Edges edges;
        for (int side = 0; side < 6; ++side)
            edges.side[static_cast<std::size_t>(side)].edge = edge_word(sides, formula::side_name(side));
        r.edges = edges;
    } else {
        r.edges = formula::Edges::all(edge_word(s, key));
    }
}

// One value for every chemical, or one a chemical.
std::vector<double> chemical_values(Settings& s, const std::string& key, int chemicals) {
    const toml::node* node = s.node(key);
    const std::string allowed = "a number, or a list of one number a chemical (" + std::to_string(chemicals) +
                                "), each from -1e30 to 1e30";
    if (node && node->is_array()) {
        const std::vector<double> v = s.numbers(key, {});
        if (static_cast<int>(v.size()) != chemicals) s.refuse(key, allowed);
        for (double x : v)
            if (!std::isfinite(x) || std::fabs(x) > 1e30) s.refuse(key, allowed);
        return v;
    }
    return std::vector<double>(static_cast<std::size_t>(chemicals), s.number_in(key, 0, -1e30, 1e30));
}

void read_edge_value(Settings& s, const std::string& key, formula::Rule& r) {
    if (!r.edges && !s.has(key)) return;  // Ready's edges: no value to say
    std::array<std::vector<double>, 6> values;
    const toml::node* node = s.node(key);
    if (const toml::table* table = node ? node->as_table() : nullptr) {
        Settings sides(s.section() + "." + key, *table,
                       side_keys("this side's value (a dirichlet side): one number, or one a chemical",
                                 "a number or a list of numbers", "from -1e30 to 1e30"));
        for (int side = 0; side < 6; ++side)
            values[static_cast<std::size_t>(side)] = chemical_values(sides, formula::side_name(side), r.chemicals);
    } else {
        values.fill(chemical_values(s, key, r.chemicals));
    }
    if (!r.edges) return;
    for (int side = 0; side < 6; ++side) {
        formula::Edges::Of& of = r.edges->side[static_cast<std::size_t>(side)];
        if (of.edge == formula::Edge::dirichlet) of.value = values[static_cast<std::size_t>(side)];
    }
}

void refuse_unrefinable(Settings& params, const FormulaModel& m, const Description& d,
                        const std::set<std::string>& words);

// What [params] gives of a formula model, besides the rule's own parameters.
struct ModelValues {
    FormulaModel model;
    std::vector<toml::table> initial;  // the overlays, read once the rule is compiled
};

const Schema<ModelValues> model_schema = [] {
    using R = formula::Rule;
    Schema<R> rule;
    rule.count("chemicals", &R::chemicals, "how many chemicals the rule has: a, b, c, ...", 1, formula::max_chemicals);
    rule.key({"formula", "the rule: Ready's formula language, a part of OpenCL C (docs/formulas.md)", "text",
              "the rule's formula, e.g. \"delta_a = laplacian_a;\"", ""},
             [](Settings& s, const std::string& key, R& r) {
                 if (s.has("kernel")) {
                     if (s.has(key)) (void)s.text(key, "");  // text, or refused naming it
                     return;  // the kernel's reader refuses both
                 }
                 r.code = s.text(key, r.code);
                 if (r.code.empty()) s.refuse(key, "\"\"", "the rule's formula, e.g. \"delta_a = laplacian_a;\"");
             });
    rule.choice(
        "accuracy", &R::accuracy,
        {{"low", formula::Accuracy::low}, {"medium", formula::Accuracy::medium}, {"high", formula::Accuracy::high}},
        "the stencils' accuracy (Ready's)");
    rule.key({"edges",
              "figgen's own edges, in place of wrap and ready_edges: periodic (a torus of any size), neumann "
              "(zero flux) or dirichlet (edge_value on the side), for every side or as a table of sides {left, "
              "right, bottom, top, back, front} (docs/formulas.md)",
              "text or a table", edges_allowed + ", or a table of them by side"},
             read_edges);
    rule.key({"edge_value", "the value on a dirichlet side: one number, one a chemical, or a table of them by side",
              "a number, a list of numbers or a table", "numbers from -1e30 to 1e30", 0.0},
             read_edge_value);
    // Where `edges` is given, wrap and ready_edges are not read: it replaces them.
    rule.key({"wrap", "true: the edges wrap around (a torus); false: they are clamped (unless edges is given)",
              "true or false", "", true},
             [](Settings& s, const std::string& key, R& r) {
                 if (!r.edges) r.wrap = s.flag(key, r.wrap);
             });
    rule.choice("data_type", &R::double_precision, {{"float", false}, {"double", true}},
                "the numbers: float (Ready's Float32) or double (Float64)");
    rule.key({"block_x", "Ready's block_size_x; see docs/formulas.md", "an integer", "4 (Ready's default) or 1", 4},
             [](Settings& s, const std::string& key, R& r) {
                 r.block_x = s.count_in(key, r.block_x, 1, 4);
                 if (r.block_x != 1 && r.block_x != 4) s.refuse(key, "4 (Ready's default) or 1");
             });
    rule.key({"ready_edges",
              "true: edges as Ready computes them (its quirks); false: a true torus, each cell clamped (unless "
              "edges is given)",
              "true or false", "", true},
             [](Settings& s, const std::string& key, R& r) {
                 if (!r.edges) r.ready_edges = s.flag(key, r.ready_edges);
             });
    rule.choice("arithmetic", &R::fused_multiply_add, {{"plain", false}, {"opencl", true}},
                "plain: every operation rounds on its own; opencl: as Ready's OpenCL compiler (clang) does it, "
                "a * b + c inside one expression is one fused multiply-add (Ready's patterns)");
    rule.choice("integrator", &R::integrator,
                {{"euler", formula::Integrator::euler},
                 {"heun", formula::Integrator::heun},
                 {"rk4", formula::Integrator::rk4}},
                "how a step advances: euler (Ready's forward Euler, first order), heun (Heun's method, second "
                "order, two stages), rk4 (classical Runge-Kutta, fourth order, four stages); each stage "
                "evaluates the whole formula");
    using M = ModelValues;
    Schema<M> s;
    s.part_at(
        rule, [](auto& v) -> auto& { return v.model.rule; });
    s.key({"kernel",
           "the rule as a whole OpenCL C kernel, in place of formula: Ready's kernel rules (docs/kernels.md); its "
           "parameters a_in, b_in, ... then a_out, b_out, ..., one work item a block of block_x cells",
           "text", "a __kernel void rd_compute(...) in the OpenCL C figgen reads (docs/kernels.md)"},
          [](Settings& section, const std::string& key, M& v) {
              if (!section.has(key)) return;
              sim::kernel::ImageRule k;
              k.text = section.text(key, "");  // text, or refused naming it
              if (section.has("formula")) section.refuse(key, "no kernel where params.formula is given: a rule is one or the other");
              if (k.text.empty()) section.refuse(key, "\"\"", "a __kernel void rd_compute(...)");
              v.model.kernel = k;
          });
    s.key({"width", "grid width in cells", "an integer",
           "an integer from 1 to " + std::to_string(formula_most_side) + ", a multiple of block_x", 128},
          [](Settings& section, const std::string& key, M& v) {
              v.model.width = section.count_in(key, v.model.width, 1, formula_most_side);
              if (v.model.width % v.model.rule.block_x != 0)
                  section.refuse(key, "a multiple of block_x (" + std::to_string(v.model.rule.block_x) + ")");
          });
    s.key({"height", "grid height in cells (1: a 1-D grid)", "an integer", integers_allowed(1, formula_most_side), 128},
          [](Settings& section, const std::string& key, M& v) {
              v.model.height = section.count_in(key, v.model.height, 1, formula_most_side);
          });
    s.key({"depth", "grid depth in cells (more than 1: a 3-D grid)", "an integer",
           integers_allowed(1, formula_most_side) + ", with width x height x depth at most " +
               std::to_string(formula_most_cells) + " cells",
           1},
          [](Settings& section, const std::string& key, M& v) {
              v.model.depth = section.count_in(key, v.model.depth, 1, formula_most_side);
              const long long cells = static_cast<long long>(v.model.width) * v.model.height * v.model.depth;
              if (cells > formula_most_cells)
                  section.refuse(key, integers_allowed(1, formula_most_side) + ", with width x height x depth at most " +
                                          std::to_string(formula_most_cells) + " cells (here " +
                                          std::to_string(cells) + ")");
          });
    s.key({"steps", "how many steps the model runs", "an integer", integers_allowed(0, 10'000'000), 1000},
          [](Settings& section, const std::string& key, M& v) {
              v.model.steps = section.count_in(key, v.model.steps, 0, 10'000'000);
          });
    s.key({"error",
           "measure the figure's error: time, the run again at half and a quarter of the timestep to the "
           "figure's last panel (as --error); space, that and a run at twice the resolution (dx / 2, "
           "timestep / 4); none",
           "text", "\"none\", \"time\" or \"space\""},
          [](Settings& section, const std::string& key, M& v) {
              if (!section.has(key)) return;
              const std::string word = section.text(key, "none");
              if (word == "none") v.model.error = FormulaModel::Error::none;
              else if (word == "time") v.model.error = FormulaModel::Error::time;
              else if (word == "space") v.model.error = FormulaModel::Error::space;
              else section.refuse(key, "\"none\", \"time\" or \"space\"");
          });
    s.key(
        {"zero_first", "the start is all zero before the overlays", "true or false", "", true},
        [](Settings& section, const std::string& key, M& v) { v.model.pattern.zero_first = section.flag(key, true); });
    s.key({"initial", "the start: Ready's overlays in order, [{chemical, operation, fill, ..., shapes}]",
           "a list of tables", "at most 1000 overlays"},
          [](Settings& section, const std::string& key, M& v) {
              v.initial = section.tables(key);
              if (v.initial.size() > 1000) section.refuse(key, "at most 1000 overlays");
          });
    return s;
}();

}  // namespace

std::vector<Key> formula_param_keys(const Description& d, const std::vector<Key>& scene_keys) {
    std::vector<Key> keys = model_schema.keys();
    const std::vector<Key> rule_keys = keys;
    keys.insert(keys.end(), scene_keys.begin(), scene_keys.end());
    // The rule's parameters: every other key of [params].
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (!is_key(rule_keys, name) && !is_key(scene_keys, name))
            keys.push_back({name, "a parameter of the rule", "a number", numbers_allowed(-1e30, 1e30)});
    }
    return keys;
}

// The rule's chemicals as the description gives them (its own reader
// checks the number): the style has keys for these alone.
int formula_chemicals(const Description& d) {
    const auto count = d.params["chemicals"].value<long long>();
    return count ? static_cast<int>(std::clamp<long long>(*count, 1, formula::max_chemicals)) : 2;
}

// `name`, read from `key` (a list of them when `listed`), as a chemical's index.
int chemical_index(Settings& s, const std::string& key, const std::string& name, int chemicals, bool listed) {
    if (name.size() == 1 && name[0] >= 'a' && name[0] < 'a' + chemicals) return name[0] - 'a';
    const std::string allowed = "a chemical of the rule: a" + std::string(chemicals > 1 ? " to " : "") +
                                (chemicals > 1 ? formula::chemical_name(chemicals - 1) : "");
    if (listed) s.refuse(key, "\"" + name + "\"", allowed);
    s.refuse(key, allowed);
}

std::set<std::string> formula_names(Settings& params, const std::string& code) {
    try {
        return formula::names_read(formula::parse(code));
    } catch (const formula::FormulaError& e) {
        params.refuse("formula", "...", "line " + std::to_string(e.pos().line) + ", column " +
                                            std::to_string(e.pos().column) + " of the formula: " + e.message());
    }
}

void refuse_clash(Settings& params, const std::string& name, int chemicals) {
    if (const auto clash = formula::parameter_name_clash(name, chemicals))
        params.refuse(name, "its name is " + *clash + "; " + formula::parameter_name_allowed);
}

namespace {

// The overlays of params.initial, read once the rule is (its chemicals and
// parameters bound them), and the stored arrays' shape against the model's.
void read_start(Settings& params, const Description& d, ModelValues& values) {
    FormulaModel& m = values.model;
    for (std::size_t i = 0; i < values.initial.size(); ++i) {
        OverlayValues overlay;
        overlay.where = "params.initial[" + std::to_string(i) + "]";
        overlay.rule = &m.rule;
        Settings s(overlay.where, values.initial[i], overlay_schema.keys());
        m.pattern.overlays.push_back(overlay_schema.read(s, overlay).overlay);
    }
    if (const auto& stored = d.stored_start) {
        const int chemicals = stored->chemical_count;
        if (chemicals != m.rule.chemicals)
            params.refuse("chemicals", "the pattern's " + std::to_string(chemicals) + ", the arrays its file stores");
        if (stored->width != m.width) params.refuse("width", "the pattern's " + std::to_string(stored->width) + ", its stored arrays'");
        if (stored->height != m.height)
            params.refuse("height", "the pattern's " + std::to_string(stored->height) + ", its stored arrays'");
        if (stored->depth != m.depth)
            params.refuse("depth", "the pattern's " + std::to_string(stored->depth) + ", its stored arrays'");
    }
}

}  // namespace

std::vector<formula::Overlay> read_overlays(const std::vector<toml::table>& initial, const formula::Rule& rule) {
    std::vector<formula::Overlay> out;
    for (std::size_t i = 0; i < initial.size(); ++i) {
        OverlayValues overlay;
        overlay.where = "params.initial[" + std::to_string(i) + "]";
        overlay.rule = &rule;
        Settings s(overlay.where, initial[i], overlay_schema.keys());
        out.push_back(overlay_schema.read(s, overlay).overlay);
    }
    return out;
}

namespace {

// A kernel rule: its kernel compiled for the grid (refusals name the
// kernel's line); none of the formula's keys that it has no use for.
FormulaModel read_kernel_model(Settings& params, const Description& d, ModelValues& values,
                               const std::vector<Key>& rule_keys, const std::vector<Key>& scene_keys,
                               const std::vector<std::pair<std::string, double>>& swept) {
    FormulaModel& m = values.model;
    const std::string why = "a kernel rule computes its own steps and edges from its text";
    for (const char* key : {"accuracy", "edges", "edge_value", "wrap", "ready_edges", "arithmetic", "integrator"})
        if (params.has(key)) params.refuse(key, "nothing: " + why);
    if (m.error != FormulaModel::Error::none)
        params.refuse("error", "\"none\": " + why + ", so figgen cannot halve its timestep or its cells");
    if (!swept.empty()) params.refuse(swept.front().first, "no sweep: a kernel rule takes no parameters");
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (is_key(rule_keys, name) || is_key(scene_keys, name)) continue;
        params.refuse(name, "no parameter: a kernel rule's numbers are in its kernel; is it a misspelt key?");
    }
    sim::kernel::ImageRule& k = *m.kernel;
    k.chemicals = m.rule.chemicals;
    k.float64 = m.rule.double_precision;
    k.block[0] = m.rule.block_x;
    try {
        m.kernel_thread_bytes = sim::kernel::thread_bytes(k, m.width, m.height, m.depth);
    } catch (const sim::kernel::KernelError& e) {
        params.refuse("kernel", "...", e.what());
    }
    read_start(params, d, values);
    return m;
}

}  // namespace

RuleRun::RuleRun(const FormulaModel& m, const std::vector<sim::Grid<double>>& start) {
    if (m.kernel) kernel_.emplace(*m.kernel, m.width, m.height, m.depth, start);
    else formula_.emplace(m.rule, m.width, m.height, m.depth, start);
}

void RuleRun::step(int steps, int threads) {
    if (formula_) return formula_->step(steps, threads);
    try {
        kernel_->step(steps, threads);
    } catch (const sim::kernel::KernelError& e) {
        throw formula::Unstable(e.what());
    }
}

sim::Grid<double> RuleRun::chemical(int i) const { return formula_ ? formula_->chemical(i) : kernel_->chemical(i); }
long long RuleRun::steps() const { return formula_ ? formula_->steps() : kernel_->steps(); }
int RuleRun::operations() const { return formula_ ? formula_->operations() : kernel_->operations(); }

FormulaModel read_formula_model(Settings& params, const Description& d, const std::vector<Key>& scene_keys,
                                const std::vector<std::pair<std::string, double>>& swept) {
    ModelValues values = model_schema.read(params);
    FormulaModel& m = values.model;
    formula::Rule& r = m.rule;
    const std::vector<Key> rule_keys = model_schema.keys();
    if (m.kernel) return read_kernel_model(params, d, values, rule_keys, scene_keys, swept);
    // The rule's parameters: each a number the formula or an overlay
    // (fill = "parameter") uses, or timestep, dx.
    std::set<std::string> words = formula_names(params, r.code);
    // An overlay's parameter fill names one of [params]: checked first, so
    // that a wrong name is said of the overlay, not of the parameter it
    // leaves unused.
    for (std::size_t i = 0; i < values.initial.size(); ++i) {
        const toml::table& t = values.initial[i];
        if (!t.contains("parameter")) continue;
        Settings s("params.initial[" + std::to_string(i) + "]", t, overlay_schema.keys());
        const std::string name = s.text("parameter", "");
        if (!d.params.contains(name) || is_key(rule_keys, name) || is_key(scene_keys, name))
            s.refuse("parameter", "the name of one of the rule's parameters");
        words.insert(name);
    }
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (is_key(rule_keys, name) || is_key(scene_keys, name)) continue;
        const double v = params.number_in(name, 0, -1e30, 1e30);
        refuse_clash(params, name, r.chemicals);
        for (const auto& sweep : swept)
            if (sweep.first == name) params.refuse(name, "no value here: the atlas sweeps " + name + " over its range");
        if (name != "timestep" && name != "dx" && !words.count(name))
            params.refuse(name, "a parameter the formula or an overlay uses (or timestep, dx); is it a misspelt key?");
        r.parameters.emplace_back(name, v);
    }
    r.parameters.insert(r.parameters.end(), swept.begin(), swept.end());
    bool has_timestep = false;
    for (const auto& p : r.parameters) has_timestep |= p.first == "timestep";
    if (!has_timestep)
        throw SettingError("params.timestep", "", "the rule's timestep: X + timestep * delta_X each step");
    try {
        r.validate(m.width, m.height, m.depth);
        const formula::Program program = formula::compile(r, formula::dimensionality(m.width, m.height, m.depth));
        m.registers = program.registers;
        m.radius_x = program.radius_x;
        m.radius_y = program.radius_y;
        m.radius_z = program.radius_z;
        m.operations = program.operations;
        m.machine_code = formula::fused::machine_code_bytes(program);
    } catch (const formula::FormulaError& e) {
        params.refuse("formula", "...", "line " + std::to_string(e.pos().line) + ", column " +
                                            std::to_string(e.pos().column) + " of the formula: " + e.message());
    } catch (const std::invalid_argument& e) {
        params.refuse("formula", "...", e.what());
    }
    // Read once the rule is: its chemicals and parameters bound the overlays'.
    read_start(params, d, values);
    if (m.error == FormulaModel::Error::space) refuse_unrefinable(params, m, d, words);
    return m;
}

namespace {

// error = "space" runs the model again at twice the resolution: refused
// where that run would not be the same model finer (a start that is cells,
// not shapes and smooth fills of fractions; a formula that reads
// neighbours by name, a cell away whatever dx is) or would not fit.
void refuse_unrefinable(Settings& params, const FormulaModel& m, const Description& d,
                        const std::set<std::string>& words) {
    const std::string why = "\"time\": \"space\" runs the model at twice the resolution, and ";
    if (d.stored_start) params.refuse("error", "\"space\"", why + "a Ready pattern's stored cells have no finer start");
    for (std::size_t i = 0; i < m.pattern.overlays.size(); ++i) {
        const formula::Overlay& o = m.pattern.overlays[i];
        const auto kind = o.fill.kind;
        if (kind == formula::Fill::Kind::white_noise || kind == formula::Fill::Kind::perlin_noise)
            params.refuse("error", "\"space\"",
                          why + "initial[" + std::to_string(i) + "]'s noise is drawn cell by cell: no finer start");
        for (const formula::Shape& shape : o.shapes)
            if (shape.kind == formula::Shape::Kind::pixel)
                params.refuse("error", "\"space\"",
                              why + "initial[" + std::to_string(i) + "] sets a pixel: no finer start");
    }
    for (const char* position : {"x_pos", "y_pos", "z_pos"})
        if (words.count(position))
            params.refuse("error", "\"space\"",
                          why + "the formula reads " + position + ", which Ready puts at a cell's corner, a place "
                                "that moves with the resolution");
    for (const std::string& name : words)
        if (name.size() > 2 && name[1] == '_' && name[0] >= 'a' && name[0] < 'a' + m.rule.chemicals &&
            name.find_first_not_of("nsewud0123456789", 2) == std::string::npos)
            params.refuse("error", "\"space\"",
                          why + "the formula reads " + name + ", a neighbour a cell away whatever dx is; its "
                                "stencils (laplacian_a, ...) scale with dx");
    const long long finer = static_cast<long long>(m.width) * 2 * (m.height > 1 ? 2 : 1) * m.height *
                            (m.depth > 1 ? 2 : 1) * m.depth;
    if (m.width * 2 > formula_most_side || m.height * 2 > formula_most_side || m.depth * 2 > formula_most_side ||
        finer > formula_most_cells)
        params.refuse("error", "\"space\"",
                      why + "the grid at twice the resolution would pass " + std::to_string(formula_most_side) +
                          " cells a side or " + std::to_string(formula_most_cells) + " cells");
}

}  // namespace

std::vector<sim::Grid<double>> formula_start(const FormulaModel& m, const Description& d,
                                             std::array<double, 3> offset) {
    std::vector<sim::Grid<double>> start(static_cast<std::size_t>(m.rule.chemicals),
                                         sim::Grid<double>(m.height * m.depth, m.width, 0.0));
    // The arrays a Ready pattern stores, when it starts from them; the
    // overlays, if any, go on top (after zeroing, if zero_first).
    if (const auto& stored = d.stored_start) {
        if (!stored->decoded()) throw std::logic_error("a pattern's stored arrays were not decoded before its run");
        for (std::size_t c = 0; c < start.size(); ++c)
            std::copy(stored->chemicals[c].begin(), stored->chemicals[c].end(), start[c].data());
    }
    if (!d.stored_start || !m.pattern.overlays.empty()) {
        sim::Random rng(d.seed);
        formula::apply_pattern(m.pattern, start, m.depth, m.rule.parameters, m.rule.double_precision, rng, offset);
    }
    return start;
}


}  // namespace scenes
