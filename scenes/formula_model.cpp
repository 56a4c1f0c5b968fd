// What the formula scenes share (scenes/formula.cpp, formula_atlas.cpp):
// a formula model read from [params] and checked before anything runs.
#include "scenes/formula_model.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "description/ready_vti.hpp"
#include "sim/formula_program.hpp"
#include "sim/random.hpp"

namespace scenes {

namespace formula = sim::formula;

namespace {

bool is_key(const std::vector<Key>& keys, const std::string& name) {
    return std::any_of(keys.begin(), keys.end(), [&](const Key& k) { return k.name == name; });
}

const std::vector<Key> rule_keys = {
    {"chemicals", "how many chemicals the rule has: a, b, c, ..."},
    {"formula", "the rule: Ready's formula language, a part of OpenCL C (docs/formulas.md)"},
    {"accuracy", "the stencils' accuracy: \"low\", \"medium\" or \"high\" (Ready's)"},
    {"wrap", "true: the edges wrap around (a torus); false: they are clamped"},
    {"data_type", "the numbers: \"float\" (Ready's Float32) or \"double\" (Float64)"},
    {"block_x", "Ready's block_size_x: 4 (its default) or 1; see docs/formulas.md"},
    {"ready_edges", "true: edges as Ready computes them (its quirks); false: a true torus, each cell clamped"},
    {"width", "grid width in cells (a multiple of block_x)"},
    {"height", "grid height in cells (Ready's 1-D stencils are not figgen's)"},
    {"steps", "how many steps the model runs"},
    {"zero_first", "the start is all zero before the overlays (else zero, too: true or false)"},
    {"initial", "the start: Ready's overlays in order, [{chemical, operation, fill, ..., shapes}]"},
};

bool is_rule_key(const std::string& key) {
    for (const Key& k : rule_keys)
        if (k.name == key) return true;
    return false;
}

// The rule's own parameters: every other key of [params].
}  // namespace

std::vector<Key> formula_param_keys(const Description& d, const std::vector<Key>& scene_keys) {
    std::vector<Key> keys = rule_keys;
    keys.insert(keys.end(), scene_keys.begin(), scene_keys.end());
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (!is_rule_key(name) && !is_key(scene_keys, name)) keys.push_back({name, "a parameter of the rule (a number)"});
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

namespace {

std::array<double, 3> point(Settings& s, const std::string& key, std::array<double, 3> fallback) {
    const std::vector<double> v = s.numbers(key, {fallback[0], fallback[1]});
    if (v.size() < 2 || v.size() > 3) s.refuse(key, "[x, y] or [x, y, z]: fractions of the grid");
    for (double x : v)
        if (!std::isfinite(x) || std::fabs(x) > 1e6) s.refuse(key, "finite numbers, fractions of the grid");
    return {v[0], v[1], v.size() > 2 ? v[2] : 0.0};
}

const std::vector<Key> overlay_keys = {
    {"chemical", "the chemical it changes: \"a\", \"b\", ..."},
    {"operation", "overwrite, add, subtract, multiply or divide"},
    {"fill", "constant, white_noise, perlin_noise, linear_gradient, radial_gradient, gaussian, sine, other_chemical or parameter"},
    {"value", "constant: the value"},
    {"low", "white_noise: the least value"},
    {"high", "white_noise: the most value"},
    {"scale", "perlin_noise: cells a feature"},
    {"octaves", "perlin_noise: octaves"},
    {"val1", "linear_gradient, radial_gradient: the value at `from`"},
    {"val2", "linear_gradient, radial_gradient: the value at `to`"},
    {"from", "gradients and sine: [x, y], a fraction of the grid"},
    {"to", "gradients and sine: [x, y], a fraction of the grid"},
    {"height", "gaussian: its height"},
    {"sigma", "gaussian: its width, a fraction of the grid's larger side"},
    {"centre", "gaussian: [x, y], a fraction of the grid"},
    {"phase", "sine: its phase, radians"},
    {"amplitude", "sine: its amplitude"},
    {"other", "other_chemical: the chemical copied"},
    {"parameter", "parameter: the rule's parameter copied"},
    {"shapes", "where: [{shape = \"everywhere\"}], circle {centre, radius}, rectangle {from, to}, pixel {at}"},
};

const std::vector<Key> shape_keys = {
    {"shape", "everywhere, rectangle, circle or pixel"},
    {"from", "rectangle: [x, y], its lower corner, a fraction of the grid"},
    {"to", "rectangle: [x, y], its upper corner, a fraction of the grid"},
    {"centre", "circle: [x, y], a fraction of the grid"},
    {"radius", "circle: a fraction of the grid's larger side"},
    {"at", "pixel: [x, y], the cell"},
};

formula::Pattern read_pattern(Settings& params, const formula::Rule& rule) {
    formula::Pattern pattern;
    pattern.zero_first = params.flag("zero_first", true);
    const auto tables = params.tables("initial");
    if (tables.size() > 1000) params.refuse("initial", "at most 1000 overlays");
    for (std::size_t i = 0; i < tables.size(); ++i) {
        const std::string where = "params.initial[" + std::to_string(i) + "]";
        Settings s(where, tables[i], overlay_keys);
        formula::Overlay o;
        o.chemical = chemical_index(s, "chemical", s.text("chemical", "a"), rule.chemicals);
        try {
            o.operation = formula::operation_named(s.text("operation", "overwrite"));
        } catch (const std::invalid_argument& e) {
            s.refuse("operation", "overwrite, add, subtract, multiply or divide");
        }
        try {
            o.fill.kind = formula::fill_named(s.text("fill", "constant"));
        } catch (const std::invalid_argument& e) {
            s.refuse("fill", overlay_keys[2].help);
        }
        formula::Fill& f = o.fill;
        const double big = 1e12;
        f.value = s.number_in("value", 0, -big, big);
        f.low = s.number_in("low", 0, -big, big);
        f.high = s.number_in("high", 1, -big, big);
        f.scale = s.number_in("scale", 64, 1e-6, big);
        f.octaves = s.count_in("octaves", 8, 1, 16);
        f.val1 = s.number_in("val1", 0, -big, big);
        f.val2 = s.number_in("val2", 1, -big, big);
        f.height = s.number_in("height", 1, -big, big);
        f.sigma = s.number_in("sigma", 0.1, 1e-9, big);
        f.phase = s.number_in("phase", 0, -big, big);
        f.amplitude = s.number_in("amplitude", 1, -big, big);
        // Every key is read and checked, whichever the fill uses.
        const auto centre = point(s, "centre", {0.5, 0.5, 0}), from = point(s, "from", {0, 0, 0});
        f.p1 = f.kind == formula::Fill::Kind::gaussian ? centre : from;
        f.p2 = point(s, "to", {1, 1, 0});
        f.chemical = chemical_index(s, "other", s.text("other", "a"), rule.chemicals);
        f.parameter = s.text("parameter", "timestep");
        bool found = false;
        for (const auto& [name, value] : rule.parameters) found |= name == f.parameter;
        if (!found) s.refuse("parameter", "the name of one of the rule's parameters");
        const auto shapes = s.tables("shapes");
        if (shapes.empty()) s.refuse("shapes", "[]", "one shape at least, e.g. [{shape = \"everywhere\"}]");
        for (std::size_t j = 0; j < shapes.size(); ++j) {
            Settings sh(where + ".shapes[" + std::to_string(j) + "]", shapes[j], shape_keys);
            formula::Shape shape;
            try {
                shape.kind = formula::shape_named(sh.text("shape", "everywhere"));
            } catch (const std::invalid_argument&) {
                sh.refuse("shape", "everywhere, rectangle, circle or pixel");
            }
            const auto middle = point(sh, "centre", {0.5, 0.5, 0}), corner = point(sh, "from", {0, 0, 0});
            shape.a = shape.kind == formula::Shape::Kind::circle ? middle : corner;
            shape.b = point(sh, "to", {1, 1, 0});
            shape.radius = sh.number_in("radius", 0.1, 0, 1e6);
            const std::vector<long long> at = sh.integers("at", {0, 0});
            if (at.size() != 2 || at[0] < 0 || at[1] < 0 || at[0] > 100000 || at[1] > 100000)
                sh.refuse("at", "[x, y]: a cell of the grid");
            shape.pixel = {static_cast<int>(at[0]), static_cast<int>(at[1]), 0};
            o.shapes.push_back(shape);
        }
        pattern.overlays.push_back(std::move(o));
    }
    return pattern;
}

}  // namespace

FormulaModel read_formula_model(Settings& params, const Description& d, const std::vector<Key>& scene_keys,
                                const std::vector<std::pair<std::string, double>>& swept) {
    FormulaModel m;
    formula::Rule& r = m.rule;
    r.chemicals = params.count_in("chemicals", 2, 1, formula::max_chemicals);
    r.code = params.text("formula", "");
    if (r.code.empty()) params.refuse("formula", "\"\"", "the rule's formula, e.g. \"delta_a = laplacian_a;\"");
    const std::string accuracy = params.text("accuracy", "medium");
    if (accuracy == "low") r.accuracy = formula::Accuracy::low;
    else if (accuracy == "medium") r.accuracy = formula::Accuracy::medium;
    else if (accuracy == "high") r.accuracy = formula::Accuracy::high;
    else params.refuse("accuracy", "\"low\", \"medium\" or \"high\"");
    r.wrap = params.flag("wrap", true);
    const std::string type = params.text("data_type", "float");
    if (type != "float" && type != "double") params.refuse("data_type", "\"float\" or \"double\"");
    r.double_precision = type == "double";
    r.block_x = params.count_in("block_x", 4, 1, 4);
    if (r.block_x != 1 && r.block_x != 4) params.refuse("block_x", "4 (Ready's default) or 1");
    r.ready_edges = params.flag("ready_edges", true);
    m.width = params.count_in("width", 128, 1, 4096);
    m.height = params.count_in("height", 128, 2, 4096);
    if (m.width % r.block_x != 0)
        params.refuse("width", "a multiple of block_x (" + std::to_string(r.block_x) + ")");
    m.steps = params.count_in("steps", 1000, 0, 10'000'000);
    // The rule's parameters: each a number the formula or an overlay
    // (fill = "parameter") uses, or timestep, dx.
    std::set<std::string> words = description::formula_words(r.code);
    if (const toml::array* initial = d.params["initial"].as_array())
        for (const toml::node& o : *initial)
            if (const toml::table* t = o.as_table())
                if (auto p = (*t)["parameter"].value<std::string>()) words.insert(*p);
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (is_rule_key(name) || is_key(scene_keys, name)) continue;
        const double v = params.number_in(name, 0, -1e30, 1e30);
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
        r.validate(m.width, m.height);
        const formula::Program program = formula::compile(r, m.width, m.height);
        m.registers = program.registers;
        m.radius_x = program.radius_x;
        m.operations = program.operations;
    } catch (const formula::FormulaError& e) {
        params.refuse("formula", "...", "line " + std::to_string(e.pos().line) + ", column " +
                                            std::to_string(e.pos().column) + " of the formula: " + e.message());
    } catch (const std::invalid_argument& e) {
        params.refuse("formula", "...", e.what());
    }
    m.pattern = read_pattern(params, r);
    if (const auto& stored = d.stored_start) {
        const auto chemicals = static_cast<int>(stored->chemicals.size());
        if (chemicals != r.chemicals)
            params.refuse("chemicals", "the pattern's " + std::to_string(chemicals) + ", the arrays its file stores");
        if (stored->width != m.width) params.refuse("width", "the pattern's " + std::to_string(stored->width) + ", its stored arrays'");
        if (stored->height != m.height)
            params.refuse("height", "the pattern's " + std::to_string(stored->height) + ", its stored arrays'");
    }
    return m;
}

std::vector<sim::Grid<double>> formula_start(const FormulaModel& m, const Description& d) {
    std::vector<sim::Grid<double>> start(static_cast<std::size_t>(m.rule.chemicals),
                                         sim::Grid<double>(m.height, m.width, 0.0));
    // The arrays a Ready pattern stores, when it starts from them; the
    // overlays, if any, go on top (after zeroing, if zero_first).
    if (const auto& stored = d.stored_start)
        for (std::size_t c = 0; c < start.size(); ++c)
            std::copy(stored->chemicals[c].begin(), stored->chemicals[c].end(), start[c].data());
    if (!d.stored_start || !m.pattern.overlays.empty()) {
        sim::Random rng(d.seed);
        formula::apply_pattern(m.pattern, start, m.rule.parameters, m.rule.double_precision, rng);
    }
    return start;
}


}  // namespace scenes
