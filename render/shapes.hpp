#pragma once
// Flat-coloured geometry (rectangles, frames, line segments, polylines,
// discs) collected as a list of primitives. A backend draws them its own
// way (render/surface.hpp): the GL canvas turns them into triangles, in
// batches, with a draw call per batch; the vector page keeps them as paths.

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/surface.hpp"

namespace render {
class Surface;
}

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
    // A segment with round ends: line(a, b) and a disc of half its width at
    // each end. Consecutive ones that meet make a smooth stroke, and the
    // vector page joins them into one path.
    void round_segment(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour);
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

    // The primitives as recorded, for backends. Points and dash lengths
    // live in shared pools that an Op indexes.
    enum class Kind : std::uint8_t { triangle, rect, frame, line, round_segment, disc, ring, polygon, polyline };
    struct Op {
        Kind kind;
        LineCap cap;                  // polyline
        std::uint32_t first = 0;      // into points(): triangle 3, rect and frame 2 (corner, size), line and
                                      // round_segment 2,
        std::uint32_t count = 0;      // disc and ring 1 (centre), polygon and polyline `count`
        std::uint32_t dash_first = 0, dash_count = 0;  // into dashes(): polyline
        float width = 0;              // frame, line, round_segment, polyline
        float a = 0, b = 0;           // disc: radius a; ring: radii a..b; polyline: dash offset b
        glm::vec4 colour;
        std::span<const glm::vec2> points(const Shapes& s) const { return {s.points_.data() + first, count}; }
        std::span<const float> dash(const Shapes& s) const { return {s.dashes_.data() + dash_first, dash_count}; }
    };
    const std::vector<Op>& ops() const { return ops_; }

    struct Vertex {
        glm::vec2 position;
        glm::vec4 colour;
    };
    // The triangles of ops [first, end) appended to `out`, three vertices each.
    void tessellate(std::size_t first, std::size_t end, std::vector<Vertex>& out) const;

    bool empty() const { return ops_.empty(); }
    // Bytes of one vertex (position and colour) as the GL backend makes and
    // uploads them, at most triangles_per_finish (render/gl/canvas.hpp) triangles at a time; line()
    // makes 6 vertices, disc() disc_vertices(radius). A recorded primitive
    // takes less than its vertices: memory estimates count vertices twice.
    static constexpr std::size_t bytes_per_vertex = sizeof(Vertex);
    static constexpr std::size_t line_vertices = 6;
    static std::size_t disc_vertices(float radius);
    static constexpr std::size_t min_disc_vertices = 3 * 12;  // a disc of radius 3.8 pixels or less
    // Makes room for `more` primitives of `points` points in all at once, so
    // that a batch of known size is one allocation.
    void reserve(std::size_t more, std::size_t points) {
        ops_.reserve(ops_.size() + more);
        points_.reserve(points_.size() + points);
    }
    void clear() {
        ops_.clear();
        points_.clear();
        dashes_.clear();
    }
    // Draws every primitive on `surface` (render/surface.hpp).
    void draw(Surface& surface) const;

private:
    Op& add(Kind kind, const glm::vec4& colour, std::initializer_list<glm::vec2> points);

    std::vector<Op> ops_;
    std::vector<glm::vec2> points_;
    std::vector<float> dashes_;
};

}  // namespace render
