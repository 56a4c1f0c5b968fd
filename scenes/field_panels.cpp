#include "scenes/field_panels.hpp"

#include <cmath>

namespace scenes {
namespace {

// The page's panel style: the scale, and the first layer's shape as the panels' aspect.
render::PanelRowStyle page_style(const std::vector<FieldPanel>& panels, double scale) {
    render::PanelRowStyle style;
    style.scale = static_cast<float>(scale);
    const FieldLayer& first = panels.front().layers.front();
    style.aspect = float(first.cols) / float(first.rows);
    return style;
}

bool any_title(const std::vector<FieldPanel>& panels) {
    for (const FieldPanel& p : panels)
        if (!p.title.empty()) return true;
    return false;
}

bool whole(float v) {
    return v == std::floor(v);
}

}  // namespace

int field_page_samples(const std::vector<FieldPanel>& panels, int width, int height, double scale) {
    const render::PanelRowStyle style = page_style(panels, scale);
    const auto rects = render::panel_grid({0, 0, float(width), float(height)}, static_cast<int>(panels.size()),
                                          static_cast<int>(panels.size()), any_title(panels), style);
    if (!whole(style.frame_width * style.scale)) return 4;
    for (const render::Rect& r : rects)
        if (!whole(r.x) || !whole(r.y) || !whole(r.w) || !whole(r.h)) return 4;
    return 1;
}

void draw_field_panels(const render::Canvas& canvas, const render::Rect& area, const std::vector<FieldPanel>& panels,
                       int columns, double scale) {
    const render::PanelRowStyle style = page_style(panels, scale);
    std::vector<std::string> titles;
    for (const FieldPanel& p : panels) titles.push_back(p.title);
    const auto rects = render::panel_grid(area, static_cast<int>(panels.size()), columns, any_title(panels), style);
    for (std::size_t i = 0; i < panels.size(); ++i)
        for (const FieldLayer& layer : panels[i].layers)
            render::draw_field(canvas, rects[i], layer.rows, layer.cols, layer.values, layer.style);
    render::draw_panel_decorations(canvas, rects, titles, style);
}

render::Image draw_field_panels(render::Canvas& canvas, const std::vector<FieldPanel>& panels, double scale) {
    canvas.clear({1, 1, 1, 1});
    draw_field_panels(canvas, {0, 0, float(canvas.width()), float(canvas.height())}, panels,
                      static_cast<int>(panels.size()), scale);
    return canvas.read();
}

render::Image draw_field_panels(const std::vector<FieldPanel>& panels, int width, int height, double scale) {
    render::Canvas canvas(width, height);  // four samples: a figure's pixels stay as they were (see field_page_samples)
    return draw_field_panels(canvas, panels, scale);
}

}  // namespace scenes
