#include "scenes/field_panels.hpp"

namespace scenes {

void draw_field_panels(const render::Canvas& canvas, const render::Rect& area, const std::vector<FieldPanel>& panels,
                       int columns, double scale) {
    render::PanelRowStyle style;
    style.scale = static_cast<float>(scale);
    const FieldLayer& first = panels.front().layers.front();
    style.aspect = float(first.cols) / float(first.rows);
    std::vector<std::string> titles;
    bool titled = false;
    for (const FieldPanel& p : panels) {
        titles.push_back(p.title);
        titled = titled || !p.title.empty();
    }
    const auto rects = render::panel_grid(area, static_cast<int>(panels.size()), columns, titled, style);
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
    render::Canvas canvas(width, height, field_panel_samples);
    return draw_field_panels(canvas, panels, scale);
}

}  // namespace scenes
