#pragma once
// Flat-coloured geometry (rectangles, frames, line segments, polylines,
// discs) collected into one vertex batch and drawn with a single draw call.

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/canvas.hpp"

namespace render {

enum class LineCap {
    butt,    // the line stops at its end points
    square,  // it goes on half its width past them (matplotlib's "projecting", its default for solid lines)
};

class Shapes {
public:
    void rect(const Rect& r, const glm::vec4& colour);
    // The outline of r, `width` pixels wide, drawn inside r's edges.
    void frame(const Rect& r, float width, const glm::vec4& colour);
    // A segment `width` pixels wide with square (butt) ends.
    void line(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour);
    void triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, const glm::vec4& colour);
    // A filled circle, a fan fine enough that its edge looks round.
    void disc(glm::vec2 centre, float radius, const glm::vec4& colour);
    // The band between two circles about `centre`.
    void ring(glm::vec2 centre, float inner_radius, float outer_radius, const glm::vec4& colour);
    // A filled convex polygon, as a fan from its first vertex.
    void convex_polygon(std::span<const glm::vec2> points, const glm::vec4& colour);
    // Connected segments `width` pixels wide, mitred at the joints; past a
    // turn of 120 degrees, or where a mitre would reach beyond a short
    // neighbouring segment, bevelled with a round fill over the outer corner.
    // Mitred joints do not overlap, so along smooth curves a translucent line
    // keeps one shade (draw_axes adds a stencil for the other joints).
    // With a dash pattern (on, off, on, ... lengths in pixels; an odd count
    // repeats twice) the dashes follow the arc length across the vertices,
    // starting `dash_offset` pixels into the pattern; each dash gets `cap`.
    void polyline(std::span<const glm::vec2> points, float width, const glm::vec4& colour,
                  std::span<const float> dash = {}, float dash_offset = 0, LineCap cap = LineCap::butt);

    bool empty() const { return vertices_.empty(); }
    // Bytes of one vertex (position and colour), here and again in the GL
    // buffer draw() fills; line() adds 6 vertices, disc() disc_vertices(radius).
    static constexpr std::size_t bytes_per_vertex = (2 + 4) * sizeof(float);
    static constexpr std::size_t line_vertices = 6;
    static std::size_t disc_vertices(float radius);
    static constexpr std::size_t min_disc_vertices = 3 * 12;  // a disc of radius 3.8 pixels or less
    // Makes room for `more` vertices at once, so that a batch of known size
    // is one allocation (not a doubling vector's 1.5 to 3 times its size).
    void reserve(std::size_t more) { vertices_.reserve(vertices_.size() + more); }
    void clear() { vertices_.clear(); }
    void draw(const Canvas& canvas) const;

private:
    void solid_polyline(std::span<const glm::vec2> points, float width, const glm::vec4& colour, LineCap cap);

    struct Vertex {
        glm::vec2 position;
        glm::vec4 colour;
    };
    std::vector<Vertex> vertices_;
};

}  // namespace render
