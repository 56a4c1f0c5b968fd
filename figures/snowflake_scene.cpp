// Hexagonal snowflakes (Liu & Zhang 1987, Figs 3-6): crystals drawn cell by
// cell as hexagons, the forbidden gaps of a restriction in a light tint,
// each panel's letter and rule code beneath it as the paper labels them.
#include <algorithm>

#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "figures/snowflake_setup.hpp"
#include "figures/step_runner.hpp"
#include "render/hex_cells.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"
#include "sim/check.hpp"

namespace figures {
namespace {

struct SnowflakeColours {
    glm::vec4 ice, tint, text;
};

struct SnowflakePanel {
    std::vector<glm::ivec2> ice;
    std::vector<glm::ivec2> forbidden;  // vapour cells in the restriction's region, drawn tinted
    int view_radius = 1;                // cells within this hex distance fit the panel
    std::string caption;
};

SnowflakePanel panel_of(const sim::Snowflake& crystal, const sim::SnowflakeParams& p, int view_radius,
                        std::string caption) {
    SnowflakePanel panel;
    for (auto c : crystal.ice_cells()) panel.ice.push_back({c.q, c.r});
    panel.view_radius = std::max(view_radius, 1);
    if (p.restriction.last >= p.restriction.first)
        for (int q = -panel.view_radius; q <= panel.view_radius; ++q)
            for (int r = -panel.view_radius; r <= panel.view_radius; ++r) {
                const sim::HexCell c{q, r};
                if (sim::hex_distance(c) <= panel.view_radius && p.restriction.in_region(c) && !crystal.is_ice(c))
                    panel.forbidden.push_back({q, r});
            }
    panel.caption = std::move(caption);
    return panel;
}

// A row of crystals in `area`, captions beneath.
void draw_snowflakes(const render::Canvas& canvas, const render::Rect& area, const std::vector<SnowflakePanel>& panels,
                     const SnowflakeColours& colours, double scale) {
    render::PanelRowStyle style;
    style.scale = static_cast<float>(scale);
    const float caption_band = 1.8f * style.title_size * style.scale;
    const render::Rect above{area.x, area.y, area.w, area.h - caption_band};
    const auto rects = render::panel_row(above, static_cast<int>(panels.size()), false, style);
    render::Font& font = render::font_of_size(std::round(style.title_size * style.scale));
    render::Text captions;
    for (std::size_t i = 0; i < panels.size(); ++i) {
        const auto view = render::fit_hex_view(rects[i], panels[i].view_radius);
        render::draw_hex_cells(canvas, view, panels[i].forbidden, colours.tint);
        render::draw_hex_cells(canvas, view, panels[i].ice, colours.ice);
        captions.add(font, panels[i].caption, {rects[i].centre().x, rects[i].bottom() + 1.3f * font.pixel_size()},
                     colours.text, render::Align::centre, render::Baseline::baseline);
    }
    captions.draw(canvas);
}

}  // namespace

void render_snowflake(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params, snowflake_keys());
    Settings style("style", d.style,
                   {{"ice_colour", "colour of the ice cells"},
                    {"tint_colour", "colour of the restriction's forbidden region"},
                    {"caption", "caption under each panel: {label}, {rule}, {step}"}});
    const std::vector<SnowflakeRun> runs = read_snowflake_runs(params, d.id);
    int steps = 0;
    try {
        steps = params.count("steps", 40);
        sim::require_integer("steps", steps, 0, 100000);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const SnowflakeColours colours{
        style_colour(style, "ice_colour", "#1d4e89"), style_colour(style, "tint_colour", "#dde8f3"), {0, 0, 0, 1}};
    const std::string caption = style.text("caption", "{label} {rule}");

    // Panels: every run at `steps`, or every run at each of figure.panels.
    Description plan = d;
    if (plan.panels.empty()) plan.panels = {steps};
    std::vector<sim::Snowflake> crystals;
    for (const auto& run : runs) crystals.emplace_back(run.params);
    std::vector<SnowflakePanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    auto caption_of = [&](std::size_t i, int step) {
        return expand(caption,
                      {{"label", runs[i].label}, {"rule", runs[i].params.rule.code()}, {"step", std::to_string(step)}});
    };
    StepRunner run(plan, options, progress);
    run.run({
        .check = {},
        .panel =
            [&](int step) {
                for (std::size_t i = 0; i < crystals.size(); ++i) {
                    const auto& c = crystals[i];
                    panels.push_back(panel_of(c, runs[i].params, c.radius() + 1, caption_of(i, step)));
                    nlohmann::json meta = snowflake_settings(runs[i].params);
                    meta.update(
                        {{"label", runs[i].label},
                         {"step", step},
                         {"statistics",
                          {{"ice", c.ice_count()}, {"radius", c.radius()}, {"euclidean_radius", c.euclidean_radius()}}},
                         {"state_sha256", snowflake_hash(c)}});
                    panel_meta.push_back(meta);
                }
            },
        .frame =
            [&](int step) {
                // A fixed view through the film: growth is at most one ring a step,
                // so the last step bounds the radius.
                std::vector<SnowflakePanel> frame;
                for (std::size_t i = 0; i < crystals.size(); ++i)
                    frame.push_back(panel_of(crystals[i], runs[i].params, run.last_step() + 1, caption_of(i, step)));
                auto& canvas = run.frame_canvas();
                canvas.clear({1, 1, 1, 1});
                draw_snowflakes(canvas, {0, 0, float(canvas.width()), float(canvas.height())}, frame, colours,
                                options.scale);
                return canvas.read();
            },
        .advance =
            [&] {
                for (auto& c : crystals) c.step();
                return true;
            },
    });

    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    draw_snowflakes(canvas, {0, 0, float(width), float(height)}, panels, colours, options.scale);
    nlohmann::json runs_meta = nlohmann::json::array();
    for (const auto& r : runs) runs_meta.push_back(r.used);
    run.write_figure(canvas.read(),
                     {{"params", params.used()}, {"runs", runs_meta}, {"style", style.used()}, {"panels", panel_meta}});
}

}  // namespace figures
