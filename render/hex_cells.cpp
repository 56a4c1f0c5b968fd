#include "render/hex_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/shapes.hpp"

namespace render {
namespace {

const float sqrt3 = std::sqrt(3.0f);

}  // namespace

HexView fit_hex_view(const Rect& area, int radius) {
    const float r = float(std::max(radius, 0));
    // Half-extents of the cells within distance r: 1.5 r + 1 sizes across,
    // sqrt(3) (r + 1/2) sizes up and down.
    const float size = std::min(area.w / 2 / (1.5f * r + 1), area.h / 2 / (sqrt3 * (r + 0.5f)));
    return {area.centre(), size};
}

glm::vec2 hex_centre(const HexView& view, glm::ivec2 cell) {
    return view.centre + view.size * glm::vec2(1.5f * float(cell.x), -sqrt3 * (float(cell.y) + 0.5f * float(cell.x)));
}

void draw_hex_cells(Surface& surface, const HexView& view, const std::vector<glm::ivec2>& cells,
                    const glm::vec4& colour) {
    if (!cells.empty()) surface.hex_cells(view, cells, colour);
}

void hex_outline(Shapes& shapes, const HexView& view, glm::ivec2 cell, float width, const glm::vec4& colour) {
    const glm::vec2 c = hex_centre(view, cell);
    // Around once and one corner further, so corner 0 gets a mitred joint too.
    std::array<glm::vec2, 8> corners;
    for (int k = 0; k < 8; ++k) {
        const float angle = glm::radians(60.0f * float(k % 6));
        corners[k] = c + view.size * glm::vec2(std::cos(angle), std::sin(angle));
    }
    shapes.polyline(corners, width, colour);
}

}  // namespace render
