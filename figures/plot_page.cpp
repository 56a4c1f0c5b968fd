#include "figures/plot_page.hpp"

#include "render/colormap.hpp"

namespace figures {

std::vector<Key> with_plot_style_keys(std::vector<Key> keys) {
    keys.insert(keys.end(), {{"plot_scale", "dpi of the printed figure / 100: scales fonts, ticks and lines"},
                             {"font_size", "tick label size in pixels at 100 dpi (matplotlib: 10 pt = 14)"},
                             {"label_size", "axis label and legend size in pixels at 100 dpi"},
                             {"bottom", "bottom edge of the plots, as a fraction of the page (matplotlib: 0.11)"}});
    return keys;
}

render::PlotStyle read_plot_style(Settings& style, double output_scale) {
    render::PlotStyle plot;
    const double plot_scale = style.number("plot_scale", 1.0);
    if (!(plot_scale >= 0.25 && plot_scale <= 8))
        throw UsageError("style.plot_scale = " + std::to_string(plot_scale) + " is not allowed: expected 0.25..8");
    plot.scale = static_cast<float>(plot_scale * output_scale);
    plot.font_size = static_cast<float>(style.number("font_size", plot.font_size));
    plot.label_size = static_cast<float>(style.number("label_size", plot.label_size));
    plot.bottom = static_cast<float>(style.number("bottom", plot.bottom));
    if (plot.font_size < 4 || plot.font_size > 100 || plot.label_size < 4 || plot.label_size > 100)
        throw UsageError("style.font_size and style.label_size must be 4..100 pixels");
    if (!(plot.bottom >= 0 && plot.bottom < plot.top))
        throw UsageError("style.bottom must be from 0 to the top margin " + std::to_string(plot.top));
    return plot;
}

void draw_plot_row(const render::Canvas& canvas, const render::Rect& area, const std::vector<render::Axes>& axes,
                   const render::PlotStyle& style) {
    const auto frames =
        render::plot_row(static_cast<int>(area.w), static_cast<int>(area.h), static_cast<int>(axes.size()), style);
    for (std::size_t i = 0; i < axes.size(); ++i) {
        render::Rect frame = frames[i];
        frame.x += area.x;
        frame.y += area.y;
        render::draw_axes(canvas, frame, axes[i], style);
    }
}

render::Image draw_plot_row(const std::vector<render::Axes>& axes, int width, int height,
                            const render::PlotStyle& style) {
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    draw_plot_row(canvas, {0, 0, float(width), float(height)}, axes, style);
    return canvas.read();
}

glm::vec4 style_colour(Settings& style, const std::string& key, const std::string& fallback) {
    try {
        return glm::vec4(render::parse_colour(style.text(key, fallback)), 1.0f);
    } catch (const std::invalid_argument& e) {
        throw UsageError("style." + key + ": " + e.what());
    }
}

std::vector<glm::vec4> style_colours(Settings& style, const std::string& key,
                                     const std::vector<std::string>& fallback) {
    std::vector<glm::vec4> colours;
    for (const std::string& name : style.texts(key, fallback)) {
        try {
            colours.push_back(glm::vec4(render::parse_colour(name), 1.0f));
        } catch (const std::invalid_argument& e) {
            throw UsageError("style." + key + ": " + e.what());
        }
    }
    if (colours.empty()) throw UsageError("style." + key + " is empty");
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

}  // namespace figures
