// Diffusion (Think Complexity 2e, Fig 7.1): one run, panels and frames taken
// from it as it passes their steps.
#include "figures/field_spec.hpp"
#include "figures/field_stats.hpp"
#include "figures/scene.hpp"
#include "figures/step_runner.hpp"
#include "sim/diffusion.hpp"

namespace figures {
namespace {

const std::vector<Key> param_keys = {
    {"n", "grid size in cells, 1..8192"},
    {"r", "diffusion rate per step, 0..0.25 (the explicit scheme's stability limit)"},
    {"boundary", "\"zero\" (the book) or \"wrap\""},
    {"block_row", "row of the initial block's top-left cell"},
    {"block_col", "column of the initial block's top-left cell"},
    {"block_size", "side of the initial block, cells"},
    {"block_value", "value of the initial block's cells"},
};

sim::DiffusionParams read_params(Settings& s) {
    sim::DiffusionParams p;
    p.n = s.count("n", p.n);
    p.r = s.number("r", p.r);
    p.boundary = sim::parse_boundary(s.text("boundary", sim::to_string(p.boundary)));
    p.block_row = s.count("block_row", p.block_row);
    p.block_col = s.count("block_col", p.block_col);
    p.block_size = s.count("block_size", p.block_size);
    p.block_value = s.number("block_value", p.block_value);
    p.validate();
    return p;
}

}  // namespace

void render_diffusion(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params, param_keys);
    Settings style("style", d.style, field_spec_keys());
    sim::DiffusionParams p;
    try {
        p = read_params(params);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const FieldSpec spec =
        read_field_spec(style, {render::colormap("Reds"), 0.0, 1.0, 0.7f, render::Sampling::nearest});
    if (d.panels.empty()) throw UsageError(d.id + ": figure.panels is empty");

    // The field and its next step, and one copy per panel.
    require_memory(d, options, {grid_need("grids of doubles", p.n, p.n, 8, 2.0 + double(d.panels.size()))});
    StepRunner run(d, options, progress);
    sim::Diffusion model(p);
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    run.run({
        .check = [&](int step) { require_finite(model.field(), "diffusion", step); },
        .panel =
            [&](int step) {
                panels.push_back({format_step(d.panel_title, step), {field_layer(model.field(), spec)}});
                panel_meta.push_back({{"step", step},
                                      {"statistics", field_statistics(model.field())},
                                      {"state_sha256", state_hash(model.field())}});
            },
        .frame =
            [&](int step) {
                return draw_field_panels(run.frame_canvas(),
                                         {{format_step(d.animation->title, step), {field_layer(model.field(), spec)}}},
                                         options.scale);
            },
        .advance =
            [&] {
                model.step();
                return true;
            },
    });
    nlohmann::json meta = {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}};
    run.write_field_figure(panels, meta);
}

}  // namespace figures
