// Elementary cellular automata side by side (Think Complexity 2e, Fig 7.6):
// rows are time, top to bottom, one panel per rule, drawn in Blues.
#include "base/digest.hpp"
#include "render/field.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/scene.hpp"
#include "sim/cell1d.hpp"
#include "sim/check.hpp"

namespace scenes {
namespace {

struct Params {
    std::vector<long long> rules{20, 50, 18};
    int width = 0;
    sim::Boundary boundary = sim::Boundary::zero;
    int rows = 1;                             // figure.panels' step + 1, given before reading
    std::vector<sim::Cell1DParams> automata;  // one per rule, each checked by the model
};

const Schema<Params> param_schema =
    Schema<Params>()
        .integers("rules", &Params::rules, "Wolfram rule numbers, one panel each")
        .count("width", &Params::width, "cells per row; 0: 2 * steps + 1, the book's default")
        .choice("boundary", &Params::boundary, sim::boundary_names(),
                "beyond the edge: zero (the book's Cell1D) or the opposite edge (its Wrap1D)")
        .check([](Settings& s, const std::string&, Params& p) {
            for (long long rule : p.rules) {
                // Checked before it becomes the model's int, which a huge number would wrap into range.
                check_model(s, [&] { sim::require_integer("rules", rule, 0, 255); });
                sim::Cell1DParams a;
                a.rule = static_cast<int>(rule);
                a.rows = p.rows;
                a.width = p.width;
                a.boundary = p.boundary;
                check_model(s, [&] { a.validate(); }, {{"rule", "rules"}});
                p.automata.push_back(a);
            }
            if (p.automata.empty()) s.refuse("rules", "one rule at least");
        });

Params rows_of(int rows) {
    Params p;
    p.rows = rows;
    return p;
}

const FieldSpec style_defaults{render::colormap("Blues"), 0.0, 1.0, 0.7f, render::Sampling::nearest};

// "[31]": figure.panels as written.
std::string steps_text(const std::vector<int>& steps) {
    std::string text = "[";
    for (std::size_t i = 0; i < steps.size(); ++i) text += (i ? ", " : "") + std::to_string(steps[i]);
    return text + "]";
}

// The one panel step is the last row shown: the automata's rows are that step + 1 (the model keeps 1..100000).
int last_row(const Description& d) {
    if (d.panels.size() != 1 || d.panels.front() > 99999)
        throw SettingError("figure.panels", steps_text(d.panels),
                           "one step from 0 to 99999, the last row shown (e.g. [31] for 32 rows)");
    return d.panels.front();
}

// Each automaton is drawn as one field of rows x columns cells: the renderer
// holds it as one texture. Too many rows is the panel step's fault, too many
// columns the width's (absent: 2 * rows + 1).
void require_automata_drawable(Settings& params, const Description& d, double rows, double cols) {
    const int most = render::max_texture_side;
    if (rows > most)
        throw SettingError("figure.panels", steps_text(d.panels),
                           "a step below " + std::to_string(most) + ": each automaton at most " +
                               std::to_string(most) + " rows (the renderer draws one field that large)");
    require_drawable(params, "width", "each automaton", rows, cols);
}

class Cell1DScene : public SceneBase {
public:
    Cell1DScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), field_spec_schema().keys(style_defaults)),
          steps_(last_row(d)),
          automata_(param_schema.read(params_, rows_of(steps_ + 1)).automata),
          spec_(field_spec_schema().read(style_, style_defaults)) {
        require_automata_drawable(params_, d, rows(), columns());
    }

    // Each CA's rows (bytes) and the panel's field of them (doubles).
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("rows of cells of a byte and a double", rows(), columns(), 9, double(automata_.size()))};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(automata_.size()));
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        for (const auto& p : automata_) {
            sim::Cell1D ca(p);
            for (int i = 0; i < steps_; ++i) ca.step();
            const auto& cells = ca.cells();
            panels.push_back(
                {expand(d_.panel_title, {{"rule", std::to_string(p.rule)}, {"step", std::to_string(steps_)}}),
                 {field_layer(cells, spec_)}});
            panel_meta.push_back({{"rule", p.rule},
                                  {"step", steps_},
                                  {"size", {cells.rows(), cells.cols()}},
                                  {"statistics", {{"on_cells", ca.on_cells()}}},
                                  {"state_sha256", base::sha256_hex(cells.data(), cells.size())}});
            progress.advance();
        }
        out.figure(field_figure(panels, d_, options_),
                   {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
        progress.finish();
    }

private:
    double rows() const { return steps_ + 1.0; }
    double columns() const { return automata_.front().width > 0 ? automata_.front().width : 2.0 * rows() + 1.0; }

    const int steps_;  // the panel step: every automaton runs that many steps
    const std::vector<sim::Cell1DParams> automata_;
    const FieldSpec spec_;
};

std::unique_ptr<Scene> read_cell1d(const Description& d, const SceneOptions& options) {
    return std::make_unique<Cell1DScene>(d, options);
}

}  // namespace

SceneInfo cell1d_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"cell1d",
            read_cell1d,
            {"colormap"},
            {
                {"/panels/*/statistics/on_cells", "on cells, rule {rule}", "integer", ""},
            }};
}

}  // namespace scenes
