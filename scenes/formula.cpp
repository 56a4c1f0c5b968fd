// Formula models (sim/formula/rule.hpp): a rule of the user's own, written as
// Ready writes its formula rules, run headless into panels and a film like
// any field figure. [params] holds the rule (chemicals, formula, accuracy,
// wrap, data_type, block_x, ready_edges), the grid (width, height), steps,
// the start (initial: Ready's overlays, in order) and, as every other key,
// the rule's own parameters; [style] says which chemicals each panel shows
// (show) and how (a_colormap, b_vmin, ... for each chemical). The model
// itself is read by scenes/helpers/formula_model.cpp.
#include "sim/formula/run.hpp"

#include <algorithm>
#include <thread>

#include "base/digest.hpp"
#include "ready/state.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/formula_model.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"

namespace scenes {
namespace {

namespace formula = sim::formula;

// How chemical c is drawn unless [style] says otherwise: one chemical shown
// through viridis, or several stacked in Reds, Blues, Greens, Purples.
FieldSpec default_spec(const std::vector<int>& shown, int c) {
    static const char* stacked[] = {"Reds", "Blues", "Greens", "Purples"};
    const auto at = std::find(shown.begin(), shown.end(), c);
    const std::size_t place = at == shown.end() ? 0 : static_cast<std::size_t>(at - shown.begin());
    return shown.size() == 1 ? FieldSpec{render::colormap("viridis"), {}, {}, 1.0f, render::Sampling::smooth}
                             : FieldSpec{render::colormap(stacked[place]), {}, {}, 0.7f, render::Sampling::smooth};
}

struct Style {
    std::vector<std::string> show{"a"};
    std::vector<int> shown{0};
    bool upper = false;
    std::vector<FieldSpec> chemicals;  // each chemical's drawing, read and checked; those shown are drawn
};

Style style_defaults(int chemicals) {
    Style s;
    for (int c = 0; c < chemicals; ++c) s.chemicals.push_back(default_spec(s.shown, c));
    return s;
}

// The rule's chemicals as the description gives them: a drawing for each.
Schema<Style> style_schema(int chemicals) {
    Schema<Style> s;
    s.key(
        {"show", "the chemicals each panel shows, stacked in this order, e.g. [\"a\", \"b\"]", "a list of strings",
         "one to four chemicals of the rule"},
        [chemicals](Settings& style, const std::string& key, Style& v) {
            v.show = style.texts(key, v.show);
            v.shown.clear();
            for (const std::string& name : v.show) v.shown.push_back(chemical_index(style, key, name, chemicals, true));
            if (v.shown.empty() || v.shown.size() > 4) style.refuse(key, "one to four chemicals, e.g. [\"a\"]");
            // The drawings' defaults follow what is shown.
            for (int c = 0; c < chemicals; ++c) v.chemicals[static_cast<std::size_t>(c)] = default_spec(v.shown, c);
        },
        [](const Style& d) { return nlohmann::json(d.show); });
    s.choice("origin", &Style::upper, {{"lower", false}, {"upper", true}},
             "where y = 0 is drawn: lower (Ready's, y up) or upper (the book's arrays, row 0 on top)");
    for (int c = 0; c < chemicals; ++c)
        s.part_at(
            field_spec_schema(), [c](auto& v) -> auto& { return v.chemicals[static_cast<std::size_t>(c)]; },
            formula::chemical_name(c) + "_");
    return s;
}

std::vector<FieldSpec> shown_specs(const Style& s) {
    std::vector<FieldSpec> specs;
    for (int c : s.shown) specs.push_back(s.chemicals[static_cast<std::size_t>(c)]);
    return specs;
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
        : SceneBase(d, options, formula_param_keys(d),
                    style_schema(formula_chemicals(d)).keys(style_defaults(formula_chemicals(d)))),
          m_(read_formula_model(params_, d)),
          s_(style_schema(m_.rule.chemicals).read(style_, style_defaults(m_.rule.chemicals))),
          specs_(shown_specs(s_)) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "the steps to show, e.g. [0, 500, 1000]");
        if (d.panels.back() > m_.steps)
            throw SettingError("figure.panels", shown_steps(d.panels), "steps up to params.steps (" +
                                                                            std::to_string(m_.steps) + ")");
        if (d.animation && d.animation->last > m_.steps)
            throw SettingError("animation.steps", std::to_string(d.animation->last),
                               "steps up to params.steps (" + std::to_string(m_.steps) + ")");
        require_drawable(params_, "width", "the grid", m_.height, m_.width);
    }

    // Two states of every chemical (rows with their halos and padding,
    // sim/formula/run.cpp), each thread's registers (a chunk of at most
    // sim::formula::chunk_lanes cells each, a line apart), the start and the grids read at a
    // stop, and a copy per panel and frame of the chemicals shown, with
    // their textures.
    std::vector<MemoryNeed> memory() const override {
        const double cell = m_.rule.double_precision ? 8 : 4, chemicals = m_.rule.chemicals;
        const double panels = static_cast<double>(d_.panels.size()) + 1;
        const double row = m_.width + 2.0 * m_.radius_x + 64 / cell;  // a row, halos and padding
        const double threads = model_threads() > 0 ? model_threads() : std::max(1u, std::thread::hardware_concurrency());
        return {grid_need("the arrays a Ready pattern stores", m_.height, m_.width, 8, d_.stored_start ? chemicals : 0),
                grid_need("the chemicals' grids", m_.height + 3, row, cell, 2 * chemicals),
                grid_need("the formula's registers", threads * (m_.registers + 1),
                          sim::formula::chunk_lanes + 64 / cell, cell, 1),
                grid_need("the start and the grids read", m_.height, m_.width, 8, 2 * chemicals),
                grid_need("panels' copies", m_.height, m_.width, 8 + field_layer_bytes_per_cell,
                          panels * static_cast<double>(s_.shown.size()))};
    }

    // One thread below 256^2 cells (the frame is drawn meanwhile), every core (0) above.
    int model_threads() const { return m_.width * m_.height < 65536 ? 1 : 0; }

    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        formula::Run model(m_.rule, m_.width, m_.height, formula_start(m_, d_));
        const int threads = model_threads();
        std::vector<sim::Grid<double>> now, drawn;  // every chemical where the run is, and those shown as drawn
        auto layers = [&](Cells cells) {
            std::vector<FieldLayer> l;
            for (std::size_t i = 0; i < s_.shown.size(); ++i) l.push_back(field_layer(drawn[i], specs_[i], cells));
            return l;
        };
        auto look = [&] {
            now.clear();
            for (int c = 0; c < m_.rule.chemicals; ++c) now.push_back(model.chemical(c));
            drawn.clear();
            for (int c : s_.shown) drawn.push_back(s_.upper ? now[c] : flipped(now[c]));
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
                [&](int step) -> FrameDrawing {
                    return run.field_frame({{format_step(d_.animation->title, step), layers(Cells::viewed)}});
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
        run.write_field_figure(panels, meta, [&] { return ready_state(now); });
    }

private:
    // The chemicals and the rule, for Ready's own files (--format vti).
    ready::ReadyState ready_state(const std::vector<sim::Grid<double>>& chemicals) const {
        ready::ReadyState s;
        s.rule_name = d_.title;
        s.description = d_.caption;
        s.formula = m_.rule.code;
        static const char* accuracy[] = {"low", "medium", "high"};
        s.accuracy = accuracy[static_cast<int>(m_.rule.accuracy)];
        s.wrap = m_.rule.wrap;
        s.block_x = m_.rule.block_x;
        s.parameters = m_.rule.parameters;
        s.active_chemical = formula::chemical_name(s_.shown.front());
        s.low = specs_.front().vmin;
        s.high = specs_.front().vmax;
        s.width = m_.width;
        s.height = m_.height;
        s.float64 = m_.rule.double_precision;
        for (const auto& g : chemicals) s.chemicals.emplace_back(g.cells().begin(), g.cells().end());
        return s;
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
                {"state_sha256", base::sha256_hex(state.data(), state.size() * sizeof(double))}};
    }

    const FormulaModel m_;
    const Style s_;
    const std::vector<FieldSpec> specs_;  // of the chemicals shown
};

std::unique_ptr<Scene> read_formula(const Description& d, const SceneOptions& options) {
    return std::make_unique<FormulaScene>(d, options);
}

}  // namespace

// A formula figure's chemicals a .. z each have a colormap.
static std::vector<std::string> formula_colormap_keys() {
    std::vector<std::string> keys;
    for (char c = 'a'; c <= 'z'; ++c) keys.push_back(std::string(1, c) + "_colormap");
    return keys;
}

// Only the chemicals of the description's rule.
static std::vector<std::string> rule_colormap_keys(const Description& d) {
    std::vector<std::string> keys = formula_colormap_keys();
    keys.resize(static_cast<std::size_t>(formula_chemicals(d)));
    return keys;
}

// The most the VTI file of the last step takes: every chemical's cells as
// doubles in base64 (zlib's blocks can only grow by a few bytes each), and
// the XML around them with the rule's name, description and formula.
static double vti_disk(const Description& d) {
    const auto value = [&](const char* key, long long fallback, long long most) {
        return static_cast<double>(std::clamp<long long>(d.params[key].value_or(fallback), 1, most));
    };
    const double cells = value("width", 128, formula_most_side) * value("height", 128, formula_most_side);
    // The texts it repeats (XML escapes a character in at most 6: &quot;).
    const double texts = static_cast<double>(d.title.size() + d.caption.size() +
                                             d.params["formula"].value_or(std::string()).size());
    // And each parameter's element: its name (counted in the formula) and value.
    return cells * formula_chemicals(d) * 8 * 1.34 * 1.01 + 65536 + 6 * texts + 200.0 * d.params.size();
}

SceneInfo formula_scene() {
    return {.name = "formula",
            .read = read_formula,
            .colormap_keys = formula_colormap_keys(),
            .colormap_keys_of = rule_colormap_keys,
            .extra_files = {{.format = "vti", .disk = vti_disk}}};
}

}  // namespace scenes
