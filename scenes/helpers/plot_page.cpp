#include "scenes/helpers/plot_page.hpp"

#include <cmath>

#include "render/colormap.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/panel_grid.hpp"

namespace scenes {

const description::Schema<PlotSettings>& plot_settings_schema() {
    static const description::Schema<PlotSettings> schema = [] {
        using P = render::PlotStyle;
        description::Schema<P> plot;
        plot.number("font_size", &P::font_size, "tick label size in pixels at 100 dpi (matplotlib: 10 pt = 14)", 4.0,
                    100.0);
        plot.number("label_size", &P::label_size, "axis label and legend size in pixels at 100 dpi", 4.0, 100.0);
        // Strictly below the top margin: a float just under it, not the double.
        plot.number("bottom", &P::bottom, "bottom edge of the plots, as a fraction of the page (matplotlib: 0.11)", 0.0,
                    std::nextafter(P{}.top, 0.0f));
        description::Schema<PlotSettings> s;
        s.number("plot_scale", &PlotSettings::plot_scale,
                 "dpi of the printed figure / 100: scales fonts, ticks and lines", 0.25, 8.0);
        s.part(plot, &PlotSettings::plot);
        return s;
    }();
    return schema;
}

render::PlotStyle plot_style(const PlotSettings& settings, double output_scale) {
    render::PlotStyle plot = settings.plot;
    plot.scale = static_cast<float>(settings.plot_scale * output_scale);
    return plot;
}

namespace {

// The plots' frames in `area`: matplotlib's subplot margins, widened where a
// plot's y tick labels and y label, as measured, need more room to the left
// of its frame than the margin or the gap leaves (matplotlib's
// constrained layout does the same), by half an em more than they need.
std::vector<render::Rect> plot_frames(const render::Rect& area, const std::vector<render::Axes>& axes,
                                      const render::PlotStyle& style) {
    const int w = static_cast<int>(area.w), h = static_cast<int>(area.h), n = static_cast<int>(axes.size());
    auto placed = [&](std::vector<render::Rect> frames) {
        for (render::Rect& frame : frames) frame.x += area.x, frame.y += area.y;
        return frames;
    };
    std::vector<render::Rect> frames = placed(render::plot_row(w, h, n, style));
    // How far each plot's text reaches left of its frame.
    std::vector<float> reach(axes.size(), 0.0f);
    for (std::size_t i = 0; i < axes.size(); ++i) {
        render::PageText page;
        render::axes_text(page, frames[i], axes[i], style, 0);
        for (const render::PageText::Box& t : page.texts)
            if (t.within < 0 && t.box.w > 0 && t.box.right() <= frames[i].x + 1)
                reach[i] = std::max(reach[i], frames[i].x - t.box.x);
    }
    const float pad = 0.5f * style.label_size * style.scale;
    float min_left = 0, min_gap = 0;
    if (!frames.empty() && reach[0] > frames[0].x - area.x) min_left = reach[0] + pad;
    for (std::size_t i = 1; i < frames.size(); ++i)
        if (reach[i] > frames[i].x - frames[i - 1].right()) min_gap = std::max(min_gap, reach[i] + pad);
    if (min_left == 0 && min_gap == 0) return frames;
    return placed(render::plot_row(w, h, n, style, min_left, min_gap));
}

}  // namespace

void draw_plot_row(render::Surface& surface, const render::Rect& area, const std::vector<render::Axes>& axes,
                   const render::PlotStyle& style) {
    const auto frames = plot_frames(area, axes, style);
    for (std::size_t i = 0; i < axes.size(); ++i) render::draw_axes(surface, frames[i], axes[i], style);
}

render::PageText plot_row_text(const render::Rect& area, const std::vector<render::Axes>& axes,
                               const render::PlotStyle& style) {
    const auto frames = plot_frames(area, axes, style);
    render::PageText page;
    for (std::size_t i = 0; i < axes.size(); ++i)
        render::axes_text(page, frames[i], axes[i], style, axes.size() > 1 ? static_cast<int>(i) + 1 : 0);
    return page;
}

FigureDrawing plot_figure(std::vector<render::Axes> axes, const Description& d, const SceneOptions& options,
                          const render::PlotStyle& style) {
    require_text_fits(
        d, options, [&](const render::Rect& area) { return plot_row_text(area, axes, style); }, plot_remedy);
    const int width = figure_width(d, options), height = figure_height(d, options);
    return {width, height, false, [axes = std::move(axes), style](render::Surface& surface) {
                surface.background({1, 1, 1, 1});
                draw_plot_row(surface, {0, 0, float(surface.width()), float(surface.height())}, axes, style);
            }};
}

Colour colour(const std::string& name) {
    const auto rgb = render::find_colour(name);
    if (!rgb) throw std::logic_error("no colour " + name);
    return {name, glm::vec4(*rgb, 1.0f)};
}

void to_json(nlohmann::json& json, const Colour& colour) {
    json = colour.name;
}

Colour read_colour(Settings& style, const std::string& key, const Colour& fallback) {
    const std::string name = style.text(key, fallback.name);
    const auto rgb = render::find_colour(name);
    if (!rgb) style.refuse(key, render::colours_allowed());
    return {name, glm::vec4(*rgb, 1.0f)};
}

std::vector<Colour> read_colours(Settings& style, const std::string& key, const std::vector<Colour>& fallback) {
    std::vector<std::string> names;
    for (const Colour& c : fallback) names.push_back(c.name);
    std::vector<Colour> colours;
    for (const std::string& name : style.texts(key, names)) {
        const auto rgb = render::find_colour(name);
        if (!rgb) style.refuse(key, "\"" + name + "\"", "a list of colours, each " + render::colours_allowed());
        colours.push_back({name, glm::vec4(*rgb, 1.0f)});
    }
    if (colours.empty()) style.refuse(key, "[]", "one colour at least");
    return colours;
}

render::Series line_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                           float width, bool dashed) {
    render::Series s;
    s.x = std::move(x);
    s.y = std::move(y);
    s.label = std::move(label);
    s.colour = colour;
    s.line_width = width;
    // matplotlib's dashed pattern: 3.7 on, 1.6 off, in line widths.
    if (dashed) s.dash = {3.7f * width, 1.6f * width};
    return s;
}

render::Series dot_series(std::vector<double> x, std::vector<double> y, std::string label, glm::vec4 colour,
                          float size) {
    render::Series s;
    s.x = std::move(x);
    s.y = std::move(y);
    s.label = std::move(label);
    s.colour = colour;
    s.line_width = 0;
    s.marker_size = size;
    return s;
}

}  // namespace scenes
