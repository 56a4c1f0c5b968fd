// Formula models (sim/formula.hpp): a rule of the user's own, written as
// Ready writes its formula rules, run headless into panels and a film like
// any field figure. [params] holds the rule (chemicals, formula, accuracy,
// wrap, data_type, block_x, ready_edges), the grid (width, height), steps,
// the start (initial: Ready's overlays, in order) and, as every other key,
// the rule's own parameters; [style] says which chemicals each panel shows
// (show) and how (a_colormap, b_vmin, ... for each chemical).
#include "sim/formula.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <thread>

#include "description/ready_vti.hpp"
#include "render/digest.hpp"
#include "scenes/field_panels.hpp"
#include "scenes/field_spec.hpp"
#include "scenes/field_stats.hpp"
#include "scenes/scene.hpp"
#include "scenes/step_runner.hpp"
#include "sim/formula_pattern.hpp"
#include "sim/formula_program.hpp"
#include "sim/random.hpp"

namespace scenes {
namespace {

namespace formula = sim::formula;

const std::vector<Key> rule_keys = {
    {"chemicals", "how many chemicals the rule has, 1..26: a, b, c, ..."},
    {"formula", "the rule: Ready's formula language, a part of OpenCL C (docs/formulas.md)"},
    {"accuracy", "the stencils' accuracy: \"low\", \"medium\" or \"high\" (Ready's)"},
    {"wrap", "true: the edges wrap around (a torus); false: they are clamped"},
    {"data_type", "the numbers: \"float\" (Ready's Float32) or \"double\" (Float64)"},
    {"block_x", "Ready's block_size_x: 4 (its default) or 1; see docs/formulas.md"},
    {"ready_edges", "true: edges as Ready computes them (its quirks); false: a true torus, each cell clamped"},
    {"width", "grid width in cells, 1..4096 (a multiple of block_x)"},
    {"height", "grid height in cells, 2..4096 (Ready's 1-D stencils are not figgen's)"},
    {"steps", "how many steps the model runs, 0..10000000"},
    {"zero_first", "the start is all zero before the overlays (else zero, too: true or false)"},
    {"initial", "the start: Ready's overlays in order, [{chemical, operation, fill, ..., shapes}]"},
};

bool is_rule_key(const std::string& key) {
    for (const Key& k : rule_keys)
        if (k.name == key) return true;
    return false;
}

// The rule's own parameters: every other key of [params].
std::vector<Key> param_keys(const Description& d) {
    std::vector<Key> keys = rule_keys;
    for (const auto& [key, value] : d.params) {
        const std::string name(key.str());
        if (!is_rule_key(name)) keys.push_back({name, "a parameter of the rule (a number)"});
    }
    return keys;
}

// The rule's chemicals as the description gives them (its own reader
// checks the number): the style has keys for these alone.
int chemicals_of(const Description& d) {
    const auto count = d.params["chemicals"].value<long long>();
    return count ? static_cast<int>(std::clamp<long long>(*count, 1, formula::max_chemicals)) : 2;
}

std::vector<Key> style_keys(const Description& d) {
    std::vector<Key> keys = {
        {"show", "the chemicals each panel shows, stacked in this order, e.g. [\"a\", \"b\"]"},
        {"origin", "where y = 0 is drawn: \"lower\" (Ready's, y up) or \"upper\" (the book's arrays, row 0 on top)"}};
    for (int i = 0; i < chemicals_of(d); ++i) {
        const auto k = field_spec_keys(formula::chemical_name(i) + "_");
        keys.insert(keys.end(), k.begin(), k.end());
    }
    return keys;
}

// `name`, read from `key` (a list of them when `listed`), as a chemical's index.
int chemical_index(Settings& s, const std::string& key, const std::string& name, int chemicals, bool listed = false) {
    if (name.size() == 1 && name[0] >= 'a' && name[0] < 'a' + chemicals) return name[0] - 'a';
    const std::string allowed = "a chemical of the rule: a" + std::string(chemicals > 1 ? " to " : "") +
                                (chemicals > 1 ? formula::chemical_name(chemicals - 1) : "");
    if (listed) s.refuse(key, "\"" + name + "\"", allowed);
    s.refuse(key, allowed);
}

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
    {"octaves", "perlin_noise: octaves, 1..16"},
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

struct Model {
    formula::Rule rule;
    int width = 128, height = 128, steps = 1000;
    formula::Pattern pattern;
    int registers = 0, radius_x = 0;  // of the compiled formula, for the memory estimate
};

Model read_model(Settings& params, const Description& d) {
    Model m;
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
        if (is_rule_key(name)) continue;
        const double v = params.number_in(name, 0, -1e30, 1e30);
        if (name != "timestep" && name != "dx" && !words.count(name))
            params.refuse(name, "a parameter the formula or an overlay uses (or timestep, dx); is it a misspelt key?");
        r.parameters.emplace_back(name, v);
    }
    bool has_timestep = false;
    for (const auto& p : r.parameters) has_timestep |= p.first == "timestep";
    if (!has_timestep)
        throw SettingError("params.timestep", "", "the rule's timestep: X + timestep * delta_X each step");
    try {
        r.validate(m.width, m.height);
        const formula::Program program = formula::compile(r, m.width, m.height);
        m.registers = program.registers;
        m.radius_x = program.radius_x;
    } catch (const formula::FormulaError& e) {
        params.refuse("formula", "...", "line " + std::to_string(e.pos().line) + ", column " +
                                            std::to_string(e.pos().column) + " of the formula: " + e.message());
    } catch (const std::invalid_argument& e) {
        params.refuse("formula", "...", e.what());
    }
    m.pattern = read_pattern(params, r);
    return m;
}

// The grid as drawn with y = 0 at the bottom (Ready's y runs up the
// screen; a panel's row 0 is its top).
sim::Grid<double> flipped(const sim::Grid<double>& g) {
    sim::Grid<double> out(g.rows(), g.cols());
    for (int y = 0; y < g.rows(); ++y)
        std::copy(g.data() + static_cast<std::size_t>(y) * g.cols(), g.data() + static_cast<std::size_t>(y + 1) * g.cols(),
                  out.data() + static_cast<std::size_t>(g.rows() - 1 - y) * g.cols());
    return out;
}

class FormulaScene : public SceneBase {
public:
    FormulaScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_keys(d), style_keys(d)), m_(read_model(params_, d)) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "the steps to show, e.g. [0, 500, 1000]");
        if (d.panels.back() > m_.steps)
            throw SettingError("figure.panels", shown_steps(d.panels), "steps up to params.steps (" +
                                                                            std::to_string(m_.steps) + ")");
        if (d.animation && d.animation->last > m_.steps)
            throw SettingError("animation.steps", std::to_string(d.animation->last),
                               "steps up to params.steps (" + std::to_string(m_.steps) + ")");
        for (const std::string& name : style_.texts("show", {"a"}))
            shown_.push_back(chemical_index(style_, "show", name, m_.rule.chemicals, true));
        if (shown_.empty() || shown_.size() > 4) style_.refuse("show", "one to four chemicals, e.g. [\"a\"]");
        // Every chemical's drawing is read (and checked), those shown kept.
        static const char* stacked[] = {"Reds", "Blues", "Greens", "Purples"};
        std::vector<FieldSpec> all;
        for (int c = 0; c < m_.rule.chemicals; ++c) {
            const auto at = std::find(shown_.begin(), shown_.end(), c);
            const std::size_t place = at == shown_.end() ? 0 : static_cast<std::size_t>(at - shown_.begin());
            const FieldSpec defaults =
                shown_.size() == 1
                    ? FieldSpec{render::colormap("viridis"), {}, {}, 1.0f, render::Sampling::smooth}
                    : FieldSpec{render::colormap(stacked[place]), {}, {}, 0.7f, render::Sampling::smooth};
            all.push_back(read_field_spec(style_, defaults, formula::chemical_name(c) + "_"));
        }
        for (int c : shown_) specs_.push_back(all[static_cast<std::size_t>(c)]);
        const std::string origin = style_.text("origin", "lower");
        if (origin != "lower" && origin != "upper") style_.refuse("origin", "\"lower\" or \"upper\"");
        upper_ = origin == "upper";
        require_drawable(params_, "width", "the grid", m_.height, m_.width);
        if (const auto& stored = d.stored_start) {
            const auto chemicals = static_cast<int>(stored->chemicals.size());
            if (chemicals != m_.rule.chemicals)
                params_.refuse("chemicals", "the pattern's " + std::to_string(chemicals) + ", the arrays its file stores");
            if (stored->width != m_.width) params_.refuse("width", "the pattern's " + std::to_string(stored->width) + ", its stored arrays'");
            if (stored->height != m_.height)
                params_.refuse("height", "the pattern's " + std::to_string(stored->height) + ", its stored arrays'");
        }
    }

    // Two states of every chemical (rows with their halos and padding,
    // sim/formula_run.cpp), each thread's registers (a chunk of at most
    // 1024 cells each, a line apart), the start and the grids read at a
    // stop, and a copy per panel and frame of the chemicals shown, with
    // their textures.
    std::vector<MemoryNeed> memory() const override {
        const double cell = m_.rule.double_precision ? 8 : 4, chemicals = m_.rule.chemicals;
        const double panels = static_cast<double>(d_.panels.size()) + 1;
        const double row = m_.width + 2.0 * m_.radius_x + 64 / cell;  // a row, halos and padding
        const double threads = model_threads() > 0 ? model_threads() : std::max(1u, std::thread::hardware_concurrency());
        return {grid_need("the chemicals' grids", m_.height + 3, row, cell, 2 * chemicals),
                grid_need("the formula's registers", threads * (m_.registers + 1), 1024 + 64 / cell, cell, 1),
                grid_need("the start and the grids read", m_.height, m_.width, 8, 2 * chemicals),
                grid_need("panels' copies", m_.height, m_.width, 8 + field_layer_bytes_per_cell,
                          panels * static_cast<double>(shown_.size()))};
    }

    // One thread below 256^2 cells (the frame is drawn meanwhile), every core (0) above.
    int model_threads() const { return m_.width * m_.height < 65536 ? 1 : 0; }

    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        sim::Random rng(d_.seed);
        std::vector<sim::Grid<double>> start(static_cast<std::size_t>(m_.rule.chemicals),
                                             sim::Grid<double>(m_.height, m_.width, 0.0));
        // The arrays a Ready pattern stores, when it starts from them; the
        // overlays, if any, go on top (after zeroing, if zero_first).
        if (const auto& stored = d_.stored_start)
            for (std::size_t c = 0; c < start.size(); ++c)
                std::copy(stored->chemicals[c].begin(), stored->chemicals[c].end(), start[c].data());
        if (!d_.stored_start || !m_.pattern.overlays.empty())
            formula::apply_pattern(m_.pattern, start, m_.rule.parameters, m_.rule.double_precision, rng);
        formula::Run model(m_.rule, m_.width, m_.height, start);
        const int threads = model_threads();
        std::vector<sim::Grid<double>> now, drawn;  // every chemical where the run is, and those shown as drawn
        auto layers = [&](Cells cells) {
            std::vector<FieldLayer> l;
            for (std::size_t i = 0; i < shown_.size(); ++i) l.push_back(field_layer(drawn[i], specs_[i], cells));
            return l;
        };
        auto look = [&] {
            now.clear();
            for (int c = 0; c < m_.rule.chemicals; ++c) now.push_back(model.chemical(c));
            drawn.clear();
            for (int c : shown_) drawn.push_back(upper_ ? now[c] : flipped(now[c]));
        };
        look();
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        run.run({
            .check = {},
            .panel =
                [&](int step) {
                    panels.push_back({format_step(d_.panel_title, step), layers(Cells::copied)});
                    panel_meta.push_back(metadata(now, step));
                },
            .frame =
                [&](int step) -> render::Canvas& {
                    return run.draw_field_frame({{format_step(d_.animation->title, step), layers(Cells::viewed)}});
                },
            .advance = {},
            .leap =
                [&](int steps) {
                    model.step(steps, threads);
                    look();
                },
        });
        nlohmann::json meta = {{"params", params_.used()},
                               {"style", style_.used()},
                               {"panels", panel_meta},
                               {"model_operations", model.operations()}};
        run.write_field_figure(panels, meta, [&] { return state_vti(now); });
    }

private:
    // The chemicals as Ready writes its own files (description/ready_vti.hpp).
    std::string state_vti(const std::vector<sim::Grid<double>>& chemicals) const {
        description::ReadyState s;
        s.rule_name = d_.title;
        s.description = d_.caption;
        s.formula = m_.rule.code;
        static const char* accuracy[] = {"low", "medium", "high"};
        s.accuracy = accuracy[static_cast<int>(m_.rule.accuracy)];
        s.wrap = m_.rule.wrap;
        s.block_x = m_.rule.block_x;
        s.parameters = m_.rule.parameters;
        s.active_chemical = formula::chemical_name(shown_.front());
        s.low = specs_.front().vmin;
        s.high = specs_.front().vmax;
        s.width = m_.width;
        s.height = m_.height;
        s.float64 = m_.rule.double_precision;
        for (const auto& g : chemicals) s.chemicals.emplace_back(g.cells().begin(), g.cells().end());
        return description::ready_vti(s);
    }

    nlohmann::json metadata(const std::vector<sim::Grid<double>>& chemicals, int step) const {
        nlohmann::json stats = nlohmann::json::object();
        std::vector<double> state;
        for (int c = 0; c < m_.rule.chemicals; ++c) {
            auto s = field_statistics(chemicals[c]);
            s.erase("sum");
            stats[formula::chemical_name(c)] = s;
            state.insert(state.end(), chemicals[c].cells().begin(), chemicals[c].cells().end());
        }
        return {{"step", step},
                {"statistics", stats},
                {"state_sha256", render::sha256_hex(state.data(), state.size() * sizeof(double))}};
    }

    const Model m_;
    std::vector<int> shown_;
    std::vector<FieldSpec> specs_;
    bool upper_ = false;
};

}  // namespace

std::unique_ptr<Scene> read_formula(const Description& d, const SceneOptions& options) {
    return std::make_unique<FormulaScene>(d, options);
}

}  // namespace scenes
