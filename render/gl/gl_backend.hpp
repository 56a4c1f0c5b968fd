#pragma once
// The GL backend's drawing, one function for each call of render/surface.hpp,
// called by Canvas. The public functions (Shapes::draw, draw_field, ...)
// check their arguments and go through the Surface, so these may assume
// checked input.

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl/canvas.hpp"

namespace render {
// Shapes, Text, FieldStyle, HexView, Tube, Facet, Camera and Light are declared by render/surface.hpp.
namespace gl_backend {

void shapes(const Canvas& canvas, const Shapes& shapes);
void text(const Canvas& canvas, const Text& text);
void field(const Canvas& canvas, const Rect& where, int rows, int cols, std::span<const std::span<const double>> layers,
           std::span<const FieldStyle* const> styles);
void hex_cells(const Canvas& canvas, const HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour);
void tubes(const Canvas& canvas, const Rect& viewport, const std::vector<Tube>& tubes,
           const std::vector<Facet>& facets, const Camera& camera, const Light& light, int sides);

}  // namespace gl_backend
}  // namespace render
