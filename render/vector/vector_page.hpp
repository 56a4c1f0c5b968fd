#pragma once
// The vector backend of render/surface.hpp: what a figure draws, recorded
// as a page of paths, glyphs and images (render/vector/vector.hpp) for the vector
// module to write as PDF or SVG.
//
//   shapes     paths, filled or stroked as cairo does it: runs of primitives
//              of one colour become one path (a plant's branches one stroke),
//              lines keep their width, caps and dashes;
//   text       the same glyphs of the same font at the same pen positions;
//   fields     one embedded image each (render::field_image): nearest fields
//              at their own cells, marked not to be smoothed;
//   hex cells  one path of hexagons a layer; cells smaller than
//              min_vector_hex_size pixels across are drawn by GL and embedded
//              as an image of the page;
//   tubes      drawn by GL, as the PNG draws them, at the page's pixels, and
//              embedded as that image (3-D has no vector form here).

#include <string>

#include "render/surface.hpp"
#include "render/vector/vector.hpp"

namespace render {

// The smallest hexagon (circumradius, pixels) drawn as a path.
inline constexpr float min_vector_hex_size = 1.0f;

class VectorPage : public Surface {
public:
    VectorPage(int width, int height, bool transparent);

    int width() const override { return page_.width; }
    int height() const override { return page_.height; }

    void background(const glm::vec4& colour) override;
    void shapes(const Shapes& shapes, Coverage coverage) override;
    void text(const Text& text) override;
    void field(const Rect& where, int rows, int cols, std::span<const double> values,
               const FieldStyle& style) override;
    void hex_cells(const HexView& view, std::span<const glm::ivec2> cells, const glm::vec4& colour) override;
    void tubes(const Rect& viewport, const std::vector<Tube>& tubes, const std::vector<Facet>& facets,
               const Camera& camera, const Light& light, int sides) override;
    void clip(const Rect& box) override;
    void unclip() override;

    vector::Page& page() { return page_; }
    const vector::Page& page() const { return page_; }

private:
    vector::Page page_;
    bool transparent_;
};

}  // namespace render
