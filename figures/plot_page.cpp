#include "figures/plot_page.hpp"

#include "render/colormap.hpp"

namespace figures {

void draw_plot_row(const render::Canvas& canvas, const render::Rect& area, const std::vector<render::Axes>& axes,
                   double scale) {
    render::PlotStyle style;
    style.scale = static_cast<float>(scale);
    const auto frames =
        render::plot_row(static_cast<int>(area.w), static_cast<int>(area.h), static_cast<int>(axes.size()), style);
    for (std::size_t i = 0; i < axes.size(); ++i) {
        render::Rect frame = frames[i];
        frame.x += area.x;
        frame.y += area.y;
        render::draw_axes(canvas, frame, axes[i], style);
    }
}

render::Image draw_plot_row(const std::vector<render::Axes>& axes, int width, int height, double scale) {
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    draw_plot_row(canvas, {0, 0, float(width), float(height)}, axes, scale);
    return canvas.read();
}

glm::vec4 style_colour(Settings& style, const std::string& key, const std::string& fallback) {
    try {
        return glm::vec4(render::parse_colour(style.text(key, fallback)), 1.0f);
    } catch (const std::invalid_argument& e) {
        throw UsageError("style." + key + ": " + e.what());
    }
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
