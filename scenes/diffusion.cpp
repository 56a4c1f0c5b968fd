// Diffusion (Think Complexity 2e, Fig 7.1): one run, panels and frames taken
// from it as it passes their steps.
#include "sim/diffusion.hpp"

#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"

namespace scenes {
namespace {

using P = sim::DiffusionParams;
const Schema<P> param_schema = Schema<P>()
                                   .count("n", &P::n, "grid size in cells")
                                   .number("r", &P::r, "diffusion rate per step")
                                   .choice("boundary", &P::boundary, sim::boundary_names(),
                                           "beyond the edge: zero (the book) or the opposite edge (a torus)")
                                   .count("block_row", &P::block_row, "row of the initial block's top-left cell")
                                   .count("block_col", &P::block_col, "column of the initial block's top-left cell")
                                   .count("block_size", &P::block_size, "side of the initial block, cells")
                                   .number("block_value", &P::block_value, "value of the initial block's cells")
                                   .check(validated<P>());

const FieldSpec style_defaults{render::colormap("Reds"), 0.0, 1.0, 0.7f, render::Sampling::nearest};

class DiffusionScene : public SceneBase {
public:
    DiffusionScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), field_spec_schema().keys(style_defaults)),
          p_(param_schema.read(params_)),
          spec_(field_spec_schema().read(style_, style_defaults)) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "one step at least");
    }

    // The field and its next step, and one copy per panel.
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("grids of doubles", p_.n, p_.n, 8, 2.0 + double(d_.panels.size())),
                grid_need("field textures", p_.n, p_.n, field_layer_bytes_per_cell, double(d_.panels.size()))};
    }

    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        sim::Diffusion model(p_);
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        // A kept panel copies the field; a frame, drawn at once, only looks at it.
        auto panel = [&](const std::string& pattern, int step, Cells cells) {
            return FieldPanel{format_step(pattern, step), {field_layer(model.field(), spec_, cells)}};
        };
        run.run({
            .check = [&](int step) { require_finite(model.field(), "diffusion", step); },
            .panel =
                [&](int step) {
                    panels.push_back(panel(d_.panel_title, step, Cells::copied));
                    panel_meta.push_back({{"step", step},
                                          {"statistics", field_statistics(model.field())},
                                          {"state_sha256", state_hash(model.field())}});
                },
            .frame = [&](int step) -> FrameDrawing { return run.field_frame({panel(d_.animation->title, step, Cells::viewed)}); },
            .advance =
                [&] {
                    model.step();
                    return true;
                },
        });
        run.write_field_figure(panels, {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
    }

private:
    const sim::DiffusionParams p_;
    const FieldSpec spec_;
};

std::unique_ptr<Scene> read_diffusion(const Description& d, const SceneOptions& options) {
    return std::make_unique<DiffusionScene>(d, options);
}

}  // namespace

SceneInfo diffusion_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"diffusion",
            read_diffusion,
            {"colormap"},
            {
                {"/panels/*/statistics/sum", "total at step {step}", "number", ""},
                {"/panels/*/statistics/max", "peak at step {step}", "number", ""},
            }};
}

}  // namespace scenes
