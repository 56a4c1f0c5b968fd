#pragma once
// Turtles that read an L-system's string into line segments.
//
// 2-D, the article's Python turtle (seeds/001): '+' turns right by the angle
// (its rt(t)), '-' left (lt(t)), '|' turns around, 'F' draws forward, 'f'
// moves without drawing, '[' pushes position, heading and width, ']' pops
// them, '!' multiplies the width by width_decay; other symbols do nothing.
// Which symbols draw and which move is the description's (Turtle2Params's
// draw and move): the Sierpinski gasket draws with F and G, the arrowhead
// with A and B.
// Headings are degrees anticlockwise from +x, so 90 is up, as turtle's seth.
//
// 3-D, The Algorithmic Beauty of Plants (ABOP) section 1.5: the frame is
// heading H, left L and up U with H x L = U; it starts with H = +y (up),
// L = -x, U = +z (towards a viewer looking down -z). '+' / '-' turn left /
// right about U, '&' / '^' pitch down / up about L, '\' / '/' roll left /
// right about H, '|' turns around about U; the signs follow ABOP's words
// (left, down), taken as rotations of the frame in its own plane.
// The apostrophe ' increments the colour index (an index into a colour
// table, kept on the bracket stack like the width), as Fig 1.25 uses it.
// Polygons, as Fig 1.25's leaves "{-f+f+f-|-f+f+f}" use them, their boundary
// traced by the turtle's moves: '{' starts a polygon whose first vertex is
// where the turtle stands; inside it, every 'F' and 'f' adds the vertex it
// moves to (an 'F' still draws its segment), and '.' adds where the turtle
// stands (ABOP ch. 5's explicit vertices); '}' ends it. A vertex equal to
// the one before (within 1e-9 of a step), or a last one equal to the first,
// is left out, so "{.f.f.}" and "{ff}" give the same triangle. Polygons nest
// (an inner '{' keeps the outer one open: ABOP's polygon stack) and are apart
// from the bracket stack: '[' and ']' inside a polygon move the turtle, not
// the polygon. One with fewer than 3 vertices encloses nothing and is
// dropped. The braces are balanced in every text (sim/lsystem.hpp), so every
// polygon ends.
//
// Both turtles count the segments with counts() before streaming the string
// and refuse when there are more than segment_budget (the 3-D one also its
// polygon vertices against vertex_budget): a figure never waits an hour or
// runs out of memory by mistake.

#include <cstdint>
#include <string>
#include <string_view>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "sim/lsystem.hpp"

namespace sim {

struct Segment2 {
    glm::dvec2 a, b;  // from, to
    double width;     // pen width, the figure's units
    int level;        // the level of the symbol that drew it (see lsystem.hpp)
};

struct Turtle2Params {
    double angle_degrees = 22;                 // turn of '+' and '-'; finite
    double length = 12;                        // step of 'F' and 'f' at level 0; > 0
    double length_scale = 1;                   // a step at level k is length * length_scale^k; > 0
    double width = 2;                          // starting pen width, rewrite reading; >= 0
    double width_per_level = 2;                // article: width_per_level * level, pensize(n*2); >= 0
    double width_decay = 0.7;                  // '!' multiplies the width by this; > 0
    glm::dvec2 start{0, 0};                    // where the turtle starts; finite
    double heading_degrees = 90;               // starting heading, anticlockwise from +x: 90 is up; finite
    std::uint64_t segment_budget = 5'000'000;  // most segments a call may make
    std::string draw = "F";                    // symbols that draw a step forward
    std::string move = "f";                    // symbols that move a step without drawing

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

// What draw and move may hold: printable symbols other than the turtle's
// commands, each at most once, none in both.
inline constexpr const char* turtle_commands = "+-|![]&^\\/";

// recursive_like_article: read the string of expand_recursive() (the
// article's f(n)/L(s, n) recursion, width from the level) instead of the
// rewritten string of expand() (width from `width` and '!'). Throws
// std::invalid_argument before any work when the segments would exceed the
// budget, or on a bad depth or parameter.
std::vector<Segment2> interpret_2d(const LSystem& system, int depth, const Turtle2Params& params,
                                   bool recursive_like_article);

// The segments a turtle would draw (its `draw` symbols, 'F' by default),
// counted without expanding; saturates at 2^64 - 1. What the budget and the
// memory estimates use.
std::uint64_t segment_count(const LSystem& system, int depth, bool recursive_like_article,
                            std::string_view draw = "F");

// Throws ParameterError naming `depth` when `segments` (segment_count's)
// exceed `budget`: what the interpreters check before they start.
void require_segment_budget(int depth, std::uint64_t segments, std::uint64_t budget);

struct Bounds2 {
    glm::dvec2 lo, hi;  // lower-left and upper-right corners; lo > hi (an empty box) for no segments
};
Bounds2 bounds(const std::vector<Segment2>& segments);  // of the end points; widths not included

struct Segment3 {
    glm::dvec3 a, b;  // from, to
    double width;     // at the time it was drawn, after any '!'
    int level;        // the level of the symbol that drew it (see lsystem.hpp)
    int colour;       // the colour index, 0 at the start, one up for each ' before it
};

struct Polygon3 {
    std::uint32_t first, count;  // its vertices: Drawing3::vertices[first, first + count), count >= 3
    int colour;                  // the colour index when its '}' was read
};

// What the 3-D turtle draws: segments, and polygons in the order they end.
struct Drawing3 {
    std::vector<Segment3> segments;
    std::vector<glm::dvec3> vertices;  // of every polygon, each polygon's together
    std::vector<Polygon3> polygons;
};

struct Turtle3Params {
    double angle_degrees = 22.5;               // every turn, pitch and roll; finite
    double length = 1;                         // step of 'F' and 'f'; > 0
    double width = 0.1;                        // starting width; >= 0
    double width_decay = 0.7;                  // '!' multiplies the width by this; > 0
    std::uint64_t segment_budget = 5'000'000;  // most segments a call may make
    std::uint64_t vertex_budget = 5'000'000;   // most polygon vertices (polygon_vertex_count) a call may make

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

// The rewrite reading only. Throws like interpret_2d, and likewise when the
// polygons' vertices would exceed vertex_budget.
Drawing3 interpret_3d(const LSystem& system, int depth, const Turtle3Params& params);

// At most how many polygon vertices the 3-D turtle records at `depth`: one
// for each '{' and each 'F', 'f' and '.' inside braces, counted without
// expanding (the dropped repeats are counted too). Saturates.
std::uint64_t polygon_vertex_count(const LSystem& system, int depth);

// Throws ParameterError naming `depth` when `vertices` exceed `budget`.
void require_vertex_budget(int depth, std::uint64_t vertices, std::uint64_t budget);

struct Bounds3 {
    glm::dvec3 lo, hi;  // the box's corners; lo > hi for no segments
};
Bounds3 bounds(const std::vector<Segment3>& segments);
Bounds3 bounds(const Drawing3& drawing);  // of the segments' end points and the polygons' vertices

// The 3-D turtle's frame, exposed so that its orthonormality can be tested.
struct TurtleFrame {
    glm::dvec3 heading{0, 1, 0};  // H
    glm::dvec3 left{-1, 0, 0};    // L
    glm::dvec3 up{0, 0, 1};       // U = H x L

    // Applies one of + - & ^ \ / | by angle_degrees; any other symbol is
    // ignored. Re-orthonormalises afterwards (H normalised, L made
    // perpendicular to it and normalised, U = H x L), so rounding cannot
    // pile up over millions of turns.
    void turn(char symbol, double angle_degrees);
    void turn(char symbol, double cos_angle, double sin_angle);  // the same with the angle's cosine and sine
};

}  // namespace sim
