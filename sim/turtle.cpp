#include "sim/turtle.hpp"

#include <array>

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/check.hpp"

namespace sim {

namespace {

constexpr double huge = 1e300;  // "any finite number" for require_number
constexpr double degrees = std::numbers::pi / 180.0;
constexpr int max_colour_index = 1 << 30;  // where ' stops counting

// 10077696 -> "10,077,696": budgets are read by people.
std::string with_commas(std::uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}


// The health check: lengths grow by length_scale per level, so a long enough
// run can overflow. Names the first segment that left the finite numbers.
template <typename Segment>
void require_finite_segments(const std::vector<Segment>& segments) {
    constexpr double most = 1e300;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const Segment& s = segments[i];
        bool finite = std::isfinite(s.width);
        for (int k = 0; k < s.a.length(); ++k)
            finite = finite && std::abs(s.a[k]) <= most && std::abs(s.b[k]) <= most;
        if (!finite)
            throw std::runtime_error("the turtle went numerically unstable at segment " + std::to_string(i + 1) +
                                     " of " + std::to_string(segments.size()) +
                                     " (a coordinate beyond 1e300); no image written");
    }
}

void require_positive(const char* name, double value) {
    if (std::isfinite(value) && value > 0) return;
    throw ParameterError(name, shown(value), "a finite number above 0");
}

// The step of a segment at each level 0..depth: length * length_scale^level.
std::vector<double> steps_by_level(const Turtle2Params& p, int depth) {
    std::vector<double> steps(static_cast<std::size_t>(depth) + 1);
    for (int k = 0; k <= depth; ++k) steps[static_cast<std::size_t>(k)] = p.length * std::pow(p.length_scale, k);
    return steps;
}

}  // namespace

void require_segment_budget(int depth, std::uint64_t segments, std::uint64_t budget) {
    if (segments <= budget) return;
    // counts() saturates: the largest count means "at least that many".
    const bool saturated = segments == std::numeric_limits<std::uint64_t>::max();
    throw ParameterError("depth", std::to_string(depth),
                         std::string("a depth within the turtle's budget (it would draw ") +
                             (saturated ? "more than " : "") + with_commas(segments) +
                             " segments, more than the budget of " + with_commas(budget) + ")");
}

std::uint64_t segment_count(const LSystem& system, int depth, bool recursive_like_article, std::string_view draw) {
    const auto counts = recursive_like_article ? system.counts_recursive(depth) : system.counts(depth);
    std::uint64_t total = 0;
    for (const char symbol : draw)
        if (const auto found = counts.find(symbol); found != counts.end())
            total = found->second > std::numeric_limits<std::uint64_t>::max() - total
                        ? std::numeric_limits<std::uint64_t>::max()
                        : total + found->second;
    return total;
}

void Turtle2Params::validate() const {
    require_number("angle_degrees", angle_degrees, -huge, huge);
    require_positive("length", length);
    require_positive("length_scale", length_scale);
    require_number("width", width, 0, huge);
    require_number("width_per_level", width_per_level, 0, huge);
    require_positive("width_decay", width_decay);
    require_number("start.x", start.x, -huge, huge);
    require_number("start.y", start.y, -huge, huge);
    require_number("heading_degrees", heading_degrees, -huge, huge);
    const std::string_view commands = turtle_commands;
    for (const auto& [name, symbols] : {std::pair{"draw", &draw}, std::pair{"move", &move}})
        for (std::size_t i = 0; i < symbols->size(); ++i) {
            const char c = (*symbols)[i];
            const bool printable = c > ' ' && c < 127;
            if (!printable || commands.find(c) != std::string_view::npos || symbols->find(c) != i ||
                (symbols == &move && draw.find(c) != std::string::npos))
                throw ParameterError(name, "\"" + *symbols + "\"",
                                     "letters and other printable symbols, each once, none of the turtle's "
                                     "commands " + std::string(commands) + " and none both drawing and moving");
        }
}

void Turtle3Params::validate() const {
    require_number("angle_degrees", angle_degrees, -huge, huge);
    require_positive("length", length);
    require_number("width", width, 0, huge);
    require_positive("width_decay", width_decay);
}

std::vector<Segment2> interpret_2d(const LSystem& system, int depth, const Turtle2Params& params,
                                   bool recursive_like_article) {
    params.validate();
    system.validate();
    const std::uint64_t segments = segment_count(system, depth, recursive_like_article, params.draw);
    require_segment_budget(depth, segments, params.segment_budget);
    // What each symbol does besides the turtle's commands: 1 draws, 2 moves.
    std::array<std::uint8_t, 256> role{};
    for (const char c : params.draw) role[static_cast<unsigned char>(c)] = 1;
    for (const char c : params.move) role[static_cast<unsigned char>(c)] = 2;

    struct Pose {
        glm::dvec2 at;
        double heading;  // degrees; sums of the angle stay exact for 22 or 22.5
        double width;
    };
    const std::vector<double> steps = steps_by_level(params, depth);
    std::vector<Segment2> out;
    out.reserve(static_cast<std::size_t>(segments));
    std::vector<Pose> stack;
    Pose pose{params.start, params.heading_degrees, params.width};
    double direction_of = std::numeric_limits<double>::quiet_NaN();  // heading `direction` was made for
    glm::dvec2 direction{0, 0};
    auto visit = [&](char c, int level) {
        if (const std::uint8_t r = role[static_cast<unsigned char>(c)]) {
            if (!(pose.heading == direction_of)) {  // cos and sin only when the heading changed
                direction = {std::cos(pose.heading * degrees), std::sin(pose.heading * degrees)};
                direction_of = pose.heading;
            }
            const glm::dvec2 to = pose.at + steps[static_cast<std::size_t>(level)] * direction;
            if (r == 1) {
                const double w = recursive_like_article ? params.width_per_level * level : pose.width;
                out.push_back({pose.at, to, w, level});
            }
            pose.at = to;
            return;
        }
        switch (c) {
            case '+':
                pose.heading -= params.angle_degrees;
                break;  // rt(t)
            case '-':
                pose.heading += params.angle_degrees;
                break;  // lt(t)
            case '|':
                pose.heading += 180;
                break;
            case '!':
                pose.width *= params.width_decay;
                break;
            case '[':
                stack.push_back(pose);
                break;
            case ']':  // balanced by validate(), so never empty
                pose = stack.back();
                stack.pop_back();
                break;
            default:
                break;
        }
    };
    if (recursive_like_article)
        system.expand_recursive(depth, visit);
    else
        system.expand(depth, visit);
    require_finite_segments(out);
    return out;
}

Bounds2 bounds(const std::vector<Segment2>& segments) {
    const double inf = std::numeric_limits<double>::infinity();
    Bounds2 box{{inf, inf}, {-inf, -inf}};
    for (const Segment2& s : segments) {
        box.lo = glm::min(box.lo, glm::min(s.a, s.b));
        box.hi = glm::max(box.hi, glm::max(s.a, s.b));
    }
    return box;
}

Bounds3 bounds(const std::vector<Segment3>& segments) {
    const double inf = std::numeric_limits<double>::infinity();
    Bounds3 box{{inf, inf, inf}, {-inf, -inf, -inf}};
    for (const Segment3& s : segments) {
        box.lo = glm::min(box.lo, glm::min(s.a, s.b));
        box.hi = glm::max(box.hi, glm::max(s.a, s.b));
    }
    return box;
}

void TurtleFrame::turn(char symbol, double angle_degrees) {
    turn(symbol, std::cos(angle_degrees * degrees), std::sin(angle_degrees * degrees));
}

// Each turn rotates two of the three axes in their plane about the third:
// x' = x cos + y sin, y' = y cos - x sin turns x towards y.
void TurtleFrame::turn(char symbol, double c, double s) {
    auto rotate = [](glm::dvec3& x, glm::dvec3& y, double cos_a, double sin_a) {
        const glm::dvec3 x0 = x;
        x = x0 * cos_a + y * sin_a;
        y = y * cos_a - x0 * sin_a;
    };
    switch (symbol) {
        case '+':
            rotate(heading, left, c, s);
            break;  // turn left: H towards L
        case '-':
            rotate(heading, left, c, -s);
            break;  // turn right
        case '&':
            rotate(heading, up, c, -s);
            break;  // pitch down: H towards -U
        case '^':
            rotate(heading, up, c, s);
            break;  // pitch up
        case '\\':
            rotate(up, left, c, s);
            break;  // roll left: U towards L
        case '/':
            rotate(up, left, c, -s);
            break;  // roll right
        case '|':   // exactly: -H, -L, U
            heading = -heading;
            left = -left;
            return;
        default:
            return;
    }
    // Gram-Schmidt: each turn is then orthonormal to rounding, never worse.
    heading = glm::normalize(heading);
    left = glm::normalize(left - glm::dot(left, heading) * heading);
    up = glm::cross(heading, left);
}

std::uint64_t polygon_vertex_count(const LSystem& system, int depth) {
    std::uint64_t starts = 0;
    const auto counts = system.counts(depth);
    if (const auto found = counts.find('{'); found != counts.end()) starts = found->second;
    const std::uint64_t moves = system.count_enclosed(depth, "Ff.");
    return moves > std::numeric_limits<std::uint64_t>::max() - starts ? std::numeric_limits<std::uint64_t>::max()
                                                                      : starts + moves;
}

void require_vertex_budget(int depth, std::uint64_t vertices, std::uint64_t budget) {
    if (vertices <= budget) return;
    const bool saturated = vertices == std::numeric_limits<std::uint64_t>::max();
    throw ParameterError("depth", std::to_string(depth),
                         std::string("a depth within the turtle's budget (its polygons would have ") +
                             (saturated ? "more than " : "") + with_commas(vertices) +
                             " vertices, more than the budget of " + with_commas(budget) + ")");
}

namespace {

// The polygons the turtle has open, innermost last: each one's vertices so
// far. Ended ones go to the drawing, each with its vertices together.
class PolygonStack {
public:
    PolygonStack(Drawing3& out, double step) : out_(out), same_(1e-9 * step) {}

    void begin(const glm::dvec3& at) { open_.push_back({at}); }
    void vertex(const glm::dvec3& at) {
        if (open_.empty()) return;  // '.' outside a polygon: nothing to add to
        std::vector<glm::dvec3>& polygon = open_.back();
        if (glm::length(at - polygon.back()) > same_) polygon.push_back(at);
    }
    void end(int colour) {  // balanced braces: never without a begin
        std::vector<glm::dvec3> polygon = std::move(open_.back());
        open_.pop_back();
        if (polygon.size() > 1 && glm::length(polygon.back() - polygon.front()) <= same_) polygon.pop_back();
        if (polygon.size() < 3) return;
        out_.polygons.push_back({std::uint32_t(out_.vertices.size()), std::uint32_t(polygon.size()), colour});
        out_.vertices.insert(out_.vertices.end(), polygon.begin(), polygon.end());
    }
    bool inside() const { return !open_.empty(); }

private:
    Drawing3& out_;
    double same_;  // vertices closer than this are one
    std::vector<std::vector<glm::dvec3>> open_;
};

}  // namespace

Drawing3 interpret_3d(const LSystem& system, int depth, const Turtle3Params& params) {
    params.validate();
    system.validate();
    const std::uint64_t segments = segment_count(system, depth, false);
    require_segment_budget(depth, segments, params.segment_budget);
    const std::uint64_t vertices = polygon_vertex_count(system, depth);
    require_vertex_budget(depth, vertices, params.vertex_budget);

    struct Pose {
        glm::dvec3 at{0, 0, 0};
        TurtleFrame frame;
        double width;
        int colour = 0;
    };
    const double c = std::cos(params.angle_degrees * degrees), s = std::sin(params.angle_degrees * degrees);
    Drawing3 out;
    out.segments.reserve(static_cast<std::size_t>(segments));
    out.vertices.reserve(static_cast<std::size_t>(vertices));
    PolygonStack polygons(out, params.length);
    std::vector<Pose> stack;
    Pose pose{};
    pose.width = params.width;
    system.expand(depth, [&](char symbol, int level) {
        switch (symbol) {
            case 'F':
            case 'f': {
                const glm::dvec3 to = pose.at + params.length * pose.frame.heading;
                if (symbol == 'F') out.segments.push_back({pose.at, to, pose.width, level, pose.colour});
                pose.at = to;
                polygons.vertex(to);
                break;
            }
            case '!':
                pose.width *= params.width_decay;
                break;
            case '\'':
                if (pose.colour < max_colour_index) ++pose.colour;  // a string may hold more ' than an int counts
                break;
            case '[':
                stack.push_back(pose);
                break;
            case ']':
                pose = stack.back();
                stack.pop_back();
                break;
            case '{':
                polygons.begin(pose.at);
                break;
            case '.':
                polygons.vertex(pose.at);
                break;
            case '}':
                polygons.end(pose.colour);
                break;
            default:
                pose.frame.turn(symbol, c, s);
                break;  // letters fall through as no-ops
        }
    });
    require_finite_segments(out.segments);
    for (const glm::dvec3& v : out.vertices)
        if (!(std::abs(v.x) <= 1e300 && std::abs(v.y) <= 1e300 && std::abs(v.z) <= 1e300))
            throw std::runtime_error("the turtle went numerically unstable at a polygon's vertex "
                                     "(a coordinate beyond 1e300); no image written");
    return out;
}

Bounds3 bounds(const Drawing3& drawing) {
    Bounds3 box = bounds(drawing.segments);
    for (const glm::dvec3& v : drawing.vertices) {
        box.lo = glm::min(box.lo, v);
        box.hi = glm::max(box.hi, v);
    }
    return box;
}

}  // namespace sim
