// Hexagonal snowflakes (Liu & Zhang 1987, Figs 3-6): crystals drawn cell by
// cell as hexagons, the forbidden gaps of a restriction in a light tint,
// each panel's letter and rule code beneath it as the paper labels them.
#include <algorithm>

#include "render/hex_cells.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/snowflake_setup.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"

namespace scenes {
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

// The crystals' panels in `area`, in rows of `columns`, each caption
// beneath its panel: a band under every row, as the paper labels them.
render::GridText snowflake_layout(const render::Rect& area, const std::vector<std::string>& captions, int columns,
                                  double scale) {
    render::PanelRowStyle style;
    style.scale = static_cast<float>(scale);
    const float caption_band = 1.8f * style.title_size * style.scale;
    const float font_pixels = std::round(style.title_size * style.scale);
    const int count = static_cast<int>(captions.size());
    const int rows = (count + columns - 1) / columns;
    const float band = area.h / float(rows);
    std::vector<render::Rect> panels;
    for (int r = 0; r < rows; ++r) {
        const render::Rect above{area.x, area.y + float(r) * band, area.w, band - caption_band};
        const auto row = render::panel_row(above, columns, false, style);
        panels.insert(panels.end(), row.begin(), row.begin() + std::min(columns, count - r * columns));
    }
    // The caption's baseline 1.3 em under the panel: its line box's top that less the ascender.
    const render::Font& font = render::font_of_size(font_pixels);
    return render::grid_text(std::move(panels), captions, render::TitlePlace::below, font_pixels,
                             1.3f * font.pixel_size() - font.ascender());
}

std::vector<std::string> captions_of(const std::vector<SnowflakePanel>& panels) {
    std::vector<std::string> captions;
    for (const SnowflakePanel& p : panels) captions.push_back(p.caption);
    return captions;
}

void draw_snowflakes(render::Surface& canvas, const render::Rect& area, const std::vector<SnowflakePanel>& panels,
                     const SnowflakeColours& colours, double scale, int columns) {
    const render::GridText layout = snowflake_layout(area, captions_of(panels), columns, scale);
    render::PanelRowStyle style;  // the caption font of the layout
    style.scale = static_cast<float>(scale);
    render::Font& font = render::font_of_size(std::round(style.title_size * style.scale));
    render::Text captions;
    for (std::size_t i = 0; i < panels.size(); ++i) {
        const render::Rect& r = layout.panels[i];
        const auto view = render::fit_hex_view(r, panels[i].view_radius);
        render::draw_hex_cells(canvas, view, panels[i].forbidden, colours.tint);
        render::draw_hex_cells(canvas, view, panels[i].ice, colours.ice);
        // At the layout's caption box, whose top is the line box's: the box that was checked is the one drawn.
        captions.add(font, panels[i].caption, {r.centre().x, layout.titles[i].y}, colours.text, render::Align::centre,
                     render::Baseline::top);
    }
    captions.draw(canvas);
}

// The figure's steps as a list, for messages: "[16, 200000]".
// The run's plan: every run at `steps`, or every run at each of
// figure.panels. No output may ask for a step past the crystal's limit.
Description plan_of(const Description& d, int steps) {
    const std::string most = std::to_string(snowflake_most_steps);
    if (!d.panels.empty() && d.panels.back() > snowflake_most_steps)
        throw SettingError("figure.panels", shown_steps(d.panels), "steps from 0 to " + most + ", ascending");
    if (d.animation && d.animation->last > snowflake_most_steps)
        throw SettingError("animation.steps", shown_steps({d.animation->first, d.animation->last}),
                           "[first, last] with 0 <= first <= last <= " + most);
    Description plan = d;
    if (plan.panels.empty()) plan.panels = {steps};
    return plan;
}

struct Params {
    SnowflakeSetup setup;
    int steps = 40;
};

const Schema<Params> param_schema = Schema<Params>()
                                        .part(snowflake_schema(), &Params::setup)
                                        .count("steps", &Params::steps, "steps of every run", 0, snowflake_most_steps);

struct Style {
    Colour ice = colour("#1d4e89"), tint = colour("#dde8f3");
    std::string caption = "{label} {rule}";
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"ice_colour", "colour of the ice cells", "a colour"}, &Style::ice, read_colour)
        .field({"tint_colour", "colour of the restriction's forbidden region", "a colour"}, &Style::tint, read_colour)
        .text("caption", &Style::caption, "caption under each panel: {label}, {rule}, {step}");

class SnowflakeScene : public SceneBase {
public:
    SnowflakeScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          colours_{s_.ice.rgba, s_.tint.rgba, {0, 0, 0, 1}},
          plan_(plan_of(d, p_.steps)) {
        require_text_fits(d, options, [&](const render::Rect& area) {
            return render::page_text(snowflake_layout(area, figure_captions(), figure_columns(area), options_.scale));
        });
    }

    // Every crystal at once, grown to the last step shown, and the panels'
    // copies of its ice (and, for a restriction, of the forbidden cells in
    // view), at most every cell within the radius.
    std::vector<MemoryNeed> memory() const override {
        int last = plan_.panels.back();
        if (d_.animation && options_.film) last = std::max(last, d_.animation->last);
        constexpr double cell = sizeof(glm::ivec2);
        double bytes = 0;
        for (const auto& run : p_.setup.runs) {
            const bool restricted = run.params.restriction.last >= run.params.restriction.first;
            bytes += snowflake_crystal_bytes(snowflake_radius_bound(run.params, last));
            for (int step : plan_.panels)
                bytes += (restricted ? 2 : 1) * cell *
                         snowflake_cells_within(snowflake_radius_bound(run.params, step) + 1);
            if (restricted && d_.animation && options_.film) bytes += 2 * cell * snowflake_cells_within(last + 1);
        }
        return {{std::to_string(p_.setup.runs.size()) + " crystals of " + std::to_string(last) + " steps", bytes},
                {"llvmpipe's queue of binned triangles", render::queued_triangles_bytes}};
    }

    void render(Output& out) const override {
        std::vector<sim::Snowflake> crystals;
        for (const auto& run : p_.setup.runs) crystals.emplace_back(run.params);
        std::vector<SnowflakePanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        StepRunner run(plan_, options_, out);
        run.run({
            .check = {},
            .panel = [&](int step) { keep_panels(crystals, step, panels, panel_meta); },
            .frame = [&](int step) { return frame_drawing(run, crystals, step); },
            .advance =
                [&] {
                    for (auto& c : crystals) c.step();
                    return true;
                },
        });

        if (run.film_only()) return run.finish_film();  // a film segment's run: no figure
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        const FigureDrawing figure{width, height, false, [&](render::Surface& surface) {
                                       surface.background({1, 1, 1, 1});
                                       const render::Rect area{0, 0, float(width), float(height)};
                                       draw_snowflakes(surface, area, panels, colours_, options_.scale,
                                                       figure_columns(area));
                                   }};
        nlohmann::json runs_meta = nlohmann::json::array();
        for (const auto& r : p_.setup.runs) runs_meta.push_back(r.used);
        // What ran: figure.panels, when given, decide the steps, not params.steps.
        run.write_figure(figure, {{"params", params_.used()},
                                  {"runs", runs_meta},
                                  {"steps_run", run.last_step()},
                                  {"style", style_.used()},
                                  {"panels", panel_meta}});
    }

private:
    // The figure's panels: every run at each step of the plan, as keep_panels adds them.
    std::vector<std::string> figure_captions() const {
        std::vector<std::string> captions;
        for (int step : plan_.panels)
            for (std::size_t i = 0; i < p_.setup.runs.size(); ++i) captions.push_back(caption_of(i, step));
        return captions;
    }

    int figure_columns(const render::Rect& area) const {
        render::PanelRowStyle style;
        style.scale = float(options_.scale);
        // A caption band under each row, counted as a title's room.
        return scenes::figure_columns(d_, area, int(plan_.panels.size() * p_.setup.runs.size()), true, style);
    }

    std::string caption_of(std::size_t i, int step) const {
        return expand(s_.caption, {{"label", p_.setup.runs[i].label},
                                   {"rule", p_.setup.runs[i].params.rule.code()},
                                   {"step", std::to_string(step)}});
    }

    // Every crystal as it is at `step`: a panel each, and its metadata.
    void keep_panels(const std::vector<sim::Snowflake>& crystals, int step, std::vector<SnowflakePanel>& panels,
                     nlohmann::json& panel_meta) const {
        for (std::size_t i = 0; i < crystals.size(); ++i) {
            const auto& c = crystals[i];
            panels.push_back(panel_of(c, p_.setup.runs[i].params, c.radius() + 1, caption_of(i, step)));
            nlohmann::json meta = snowflake_settings(p_.setup.runs[i].params);
            meta.update({{"label", p_.setup.runs[i].label},
                         {"step", step},
                         {"statistics",
                          {{"ice", c.ice_count()}, {"radius", c.radius()}, {"euclidean_radius", c.euclidean_radius()}}},
                         {"state_sha256", snowflake_hash(c)}});
            panel_meta.push_back(meta);
        }
    }

    FrameDrawing frame_drawing(const StepRunner& run, const std::vector<sim::Snowflake>& crystals, int step) const {
        // A fixed view through the film: growth is at most one ring a step,
        // so the last step bounds the radius.
        std::vector<SnowflakePanel> frame;
        for (std::size_t i = 0; i < crystals.size(); ++i)
            frame.push_back(panel_of(crystals[i], p_.setup.runs[i].params, run.last_step() + 1, caption_of(i, step)));
        return {[this, frame = std::move(frame)](render::Surface& surface) {
            surface.background({1, 1, 1, 1});
            draw_snowflakes(surface, {0, 0, float(surface.width()), float(surface.height())}, frame, colours_,
                            options_.scale, int(frame.size()));
        }};
    }

    const Params p_;
    const Style s_;
    const SnowflakeColours colours_;
    const Description plan_;  // d_ with the panels the run shows
};

std::unique_ptr<Scene> read_snowflake(const Description& d, const SceneOptions& options) {
    return std::make_unique<SnowflakeScene>(d, options);
}

}  // namespace

SceneInfo snowflake_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"snowflake",
            read_snowflake,
            {},
            {
                {"/panels/*/statistics/ice", "ice cells, {label} {rule}, step {step}", "integer", ""},
            }};
}

}  // namespace scenes
