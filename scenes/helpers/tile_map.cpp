#include "scenes/helpers/tile_map.hpp"

#include <algorithm>

namespace scenes {

render::Rect TileMap::frame(const render::Rect& area, const render::PlotStyle& plot) const {
    render::Rect frame = render::plot_row(static_cast<int>(area.w), static_cast<int>(area.h), 1, plot)[0];
    frame.x += area.x;
    frame.y += area.y;
    float side = std::min(frame.w, frame.h);
    const float room = bar ? render::colour_bar_room(*bar, side, side, plot) : 0.0f;
    side = std::max(1.0f, std::min(side, frame.w - room));
    frame.x += (frame.w - side - room) / 2;
    frame.w = frame.h = side;
    return frame;
}

render::PageText TileMap::text(const render::Rect& area, const render::PlotStyle& plot) const {
    const render::Rect f = frame(area, plot);
    render::PageText page;
    render::axes_text(page, f, axes, plot, 0);
    if (bar) render::colour_bar_text(page, f, *bar, plot, 0);
    return page;
}

void TileMap::draw(render::Surface& surface, const render::PlotStyle& plot,
                   const std::function<Tile(int t, std::vector<double>& values)>& tile) const {
    surface.background({1, 1, 1, 1});
    const render::Rect f = frame({0, 0, float(surface.width()), float(surface.height())}, plot);
    const float tw = f.w / float(columns), th = f.h / float(rows);
    std::vector<double> values;  // one tile's, reused
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            const Tile t = tile(r * columns + c, values);
            render::draw_field(surface, {f.x + c * tw, f.y + r * th, tw, th}, t.rows, t.cols, values, t.style);
        }
    render::draw_axes(surface, f, axes, plot);
    if (bar) render::draw_colour_bar(surface, f, *bar, plot);
}

}  // namespace scenes
