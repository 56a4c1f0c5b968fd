// Percolation as the book's cellular automaton (Think Complexity 2e, Fig 7.5):
// blocked 0, porous 1, wet 5, drawn in Blues from 0 to 5. tc7-5: one small
// model, panels after the first steps, the animation to the end.
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/percolation_common.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/random.hpp"

namespace scenes {
namespace {

struct Params {
    sim::PercolationParams model;
    StopRule stop = StopRule::bottom_or_fixed_point;
};
const Schema<Params> param_schema = [] {
    Schema<Params> s;
    s.part(percolation_schema(), &Params::model);
    add_stop_key(s, &Params::stop);
    return s;
}();

class PercolationScene : public SceneBase {
public:
    PercolationScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), field_spec_schema().keys(default_percolation_spec())),
          p_(param_schema.read(params_)),
          spec_(field_spec_schema().read(style_, default_percolation_spec())) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "one step at least");
    }

    // The cells, their next step and a copy per panel.
    std::vector<MemoryNeed> memory() const override {
        // The model's grids, each panel's values as doubles and its texture.
        return {grid_need("grids of bytes", p_.model.n, p_.model.n, 1, 2.0 + double(d_.panels.size())),
                grid_need("field panels", p_.model.n, p_.model.n, 8 + field_layer_bytes_per_cell,
                          double(d_.panels.size()))};
    }

    void render(Output& out) const override {
        sim::Random rng(d_.seed);
        sim::Percolation model(p_.model, rng);
        bool stopped = false;

        StepRunner run(d_, options_, out);
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        auto title = [&](const std::string& pattern) {
            return format_step(pattern, model.steps()) + (stopped ? " (stopped)" : "");
        };
        auto panel = [&] {
            panels.push_back({title(d_.panel_title), {field_layer(model.cells(), spec_)}});
            panel_meta.push_back(panel_metadata(model, p_.stop, stopped));
        };
        const int reached = run.run({
            .check = {},
            .panel = [&](int) { panel(); },
            .frame = [&](int) -> FrameDrawing {
                return run.field_frame({{title(d_.animation->title), {field_layer(model.cells(), spec_)}}});
            },
            .advance =
                [&] {
                    stopped = !step_until_stop(model, p_.stop);
                    return !stopped;
                },
        });
        // Panels asked for after the run stopped show its final state, titled with
        // the step it stopped at.
        for (int step : d_.panels)
            if (step > reached) panel();
        run.write_field_figure(panels, {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
    }

private:
    const Params p_;
    const FieldSpec spec_;
};

std::unique_ptr<Scene> read_percolation(const Description& d, const SceneOptions& options) {
    return std::make_unique<PercolationScene>(d, options);
}

}  // namespace

SceneInfo percolation_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"percolation",
            read_percolation,
            {"colormap"},
            {
                {"/panels/*/statistics/wet", "wet cells after step {step}", "integer", ""},
            }};
}

}  // namespace scenes
