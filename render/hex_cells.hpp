#pragma once
// Cells of a hexagonal lattice drawn as true hexagons: flat-topped, so the
// lattice's six directions point at 30, 90, 150, ... degrees and a snowflake
// grown along them has one arm straight up. A layer of cells is one
// instanced draw call, however many cells it holds.
//
// Axial coordinates (q, r): the centre of cell (q, r) lies at
// size * (1.5 q, sqrt(3) (r + q / 2)) from the seed, y up; `size` is the
// hexagon's circumradius, so neighbouring centres are sqrt(3) size apart.

#include <vector>

#include <glm/glm.hpp>

#include "render/surface.hpp"
#include "render/shapes.hpp"

namespace render {

struct HexView {
    glm::vec2 centre;  // pixel position of cell (0, 0)
    float size = 1;    // hexagon circumradius in pixels
};

// The view in which every cell within hex distance `radius` of the seed fits `area`, centred.
HexView fit_hex_view(const Rect& area, int radius);

// Pixel centre of a cell (y down, as everywhere in render/).
glm::vec2 hex_centre(const HexView& view, glm::ivec2 cell);

// Fills each cell's hexagon with `colour`.
void draw_hex_cells(Surface& surface, const HexView& view, const std::vector<glm::ivec2>& cells,
                    const glm::vec4& colour);

// The outline of one cell's hexagon, for schematics.
void hex_outline(Shapes& shapes, const HexView& view, glm::ivec2 cell, float width, const glm::vec4& colour);

}  // namespace render
