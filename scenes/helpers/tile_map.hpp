#pragma once
// A map of tiles, as the atlases draw them (gs-atlas, formula atlases):
// columns x rows fields in a square plot frame, row 0 at the top, the axes
// drawn over them and a colour bar beside.

#include <functional>
#include <optional>
#include <vector>

#include "render/field.hpp"
#include "render/plot.hpp"

namespace scenes {

struct TileMap {
    int columns = 1, rows = 1;
    render::Axes axes;
    std::optional<render::ColourBar> bar;

    // The plot frame in `area` that holds the tiles: square, it and the
    // colour bar beside it centred.
    render::Rect frame(const render::Rect& area, const render::PlotStyle& plot) const;
    // The text it draws there (axes, colour bar), for require_text_fits.
    render::PageText text(const render::Rect& area, const render::PlotStyle& plot) const;

    // One tile as drawn: its field (values filled in by the caller) and style.
    struct Tile {
        int rows = 1, cols = 1;
        render::FieldStyle style;
    };
    // Draws the page: `tile(t, values)` fills tile t's values (row-major,
    // t counted row by row from the top) and says how to draw them.
    void draw(render::Surface& surface, const render::PlotStyle& plot,
              const std::function<Tile(int t, std::vector<double>& values)>& tile) const;
};

}  // namespace scenes
