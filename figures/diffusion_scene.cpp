// Diffusion (Think Complexity 2e, Fig 7.1): one run, panels and frames taken
// from it as it passes their steps.
#include <algorithm>
#include <memory>
#include <stdexcept>

#include "figures/field_panels.hpp"
#include "figures/field_stats.hpp"
#include "figures/scene.hpp"
#include "sim/diffusion.hpp"

namespace figures {
namespace {

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

const std::vector<Key> param_keys = {
    {"n", "grid size in cells, 1..8192"},
    {"r", "diffusion rate per step, 0..0.25 (the explicit scheme's stability limit)"},
    {"boundary", "\"zero\" (the book) or \"wrap\""},
    {"block_row", "row of the initial block's top-left cell"},
    {"block_col", "column of the initial block's top-left cell"},
    {"block_size", "side of the initial block, cells"},
    {"block_value", "value of the initial block's cells"},
};

const std::vector<Key> style_keys = {
    {"colormap", "Reds, Blues, Greens or viridis"},
    {"vmin", "value of the colormap's first colour"},
    {"vmax", "value of the colormap's last colour"},
    {"alpha", "opacity over white, 0..1"},
    {"sampling", "\"nearest\" or \"smooth\""},
};

render::FieldStyle read_style(Settings& s) {
    render::FieldStyle style;
    style.colormap = &render::colormap(s.text("colormap", "Reds"));
    style.vmin = s.number("vmin", 0.0);
    style.vmax = s.number("vmax", 1.0);
    if (!(style.vmax > style.vmin)) throw UsageError("style.vmax must be greater than style.vmin");
    const double alpha = s.number("alpha", 0.7);
    if (alpha < 0 || alpha > 1) throw UsageError("style.alpha = " + std::to_string(alpha) + " is not allowed: expected 0..1");
    style.alpha = static_cast<float>(alpha);
    const std::string sampling = s.text("sampling", "nearest");
    if (sampling != "nearest" && sampling != "smooth")
        throw UsageError("style.sampling = \"" + sampling + "\" is not allowed: use \"nearest\" or \"smooth\"");
    style.sampling = sampling == "smooth" ? render::Sampling::smooth : render::Sampling::nearest;
    return style;
}

FieldPanel panel_of(const sim::Grid<double>& field, const render::FieldStyle& style, std::string title) {
    return {std::move(title), {{field.rows(), field.cols(), field.cells(), style}}};
}

}  // namespace

void render_diffusion(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params, param_keys);
    Settings style_settings("style", d.style, style_keys);
    sim::DiffusionParams p;
    render::FieldStyle style;
    try {
        p = read_params(params);
        style = read_style(style_settings);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (d.panels.empty()) throw UsageError(d.id + ": figure.panels is empty");

    const bool animate = d.animation && options.animates();
    const int last = d.last_step(animate);
    progress.start(d.id, last + 1 + (animate ? d.animation->frame_count() : 0));

    std::unique_ptr<FrameSink> frames;
    if (animate)
        frames = std::make_unique<FrameSink>(d, options, scaled_even(d.animation->width, options.scale),
                                             scaled_even(d.animation->height, options.scale));
    sim::Diffusion model(p);
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    for (int step = 0;; ++step) {
        const bool is_panel = std::find(d.panels.begin(), d.panels.end(), step) != d.panels.end();
        const bool is_frame = animate && d.animation->shows(step);
        if (is_panel || is_frame) require_finite(model.field(), "diffusion", step);
        if (is_panel) {
            panels.push_back(panel_of(model.field(), style, format_step(d.panel_title, step)));
            panel_meta.push_back({{"step", step},
                                  {"statistics", field_statistics(model.field())},
                                  {"state_sha256", state_hash(model.field())}});
        }
        if (is_frame) {
            frames->add(draw_field_panels({panel_of(model.field(), style, format_step(d.animation->title, step))},
                                          scaled_even(d.animation->width, options.scale),
                                          scaled_even(d.animation->height, options.scale), options.scale),
                        step);
            progress.advance();
        }
        if (step == last) break;
        model.step();
        progress.advance();
    }
    progress.advance();

    nlohmann::json meta = {{"params", params.used()}, {"style", style_settings.used()}, {"panels", panel_meta}};
    if (frames) meta["animation"] = frames->finish();
    const render::Image image = draw_field_panels(panels, scaled_even(d.width, options.scale),
                                                  scaled_even(d.height, options.scale), options.scale);
    write_figure(d, options, image, meta);
    progress.finish();
}

}  // namespace figures
