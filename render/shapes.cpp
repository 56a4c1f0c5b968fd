#include "render/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "render/surface.hpp"

namespace render {
Shapes::Op& Shapes::add(Kind kind, const glm::vec4& colour, std::initializer_list<glm::vec2> points) {
    Op& op = ops_.emplace_back();
    op.kind = kind;
    op.cap = LineCap::butt;
    op.colour = colour;
    op.first = static_cast<std::uint32_t>(points_.size());
    op.count = static_cast<std::uint32_t>(points.size());
    points_.insert(points_.end(), points);
    return op;
}

void Shapes::triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, const glm::vec4& colour) {
    add(Kind::triangle, colour, {a, b, c});
}

void Shapes::rect(const Rect& r, const glm::vec4& colour) { add(Kind::rect, colour, {{r.x, r.y}, {r.w, r.h}}); }

void Shapes::frame(const Rect& r, float width, const glm::vec4& colour) {
    add(Kind::frame, colour, {{r.x, r.y}, {r.w, r.h}}).width = width;
}

void Shapes::line(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour) {
    if (glm::length(b - a) == 0.0f) return;
    add(Kind::line, colour, {a, b}).width = width;
}

void Shapes::round_segment(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour) {
    if (!(width > 0)) return;
    add(Kind::round_segment, colour, {a, b}).width = width;
}

void Shapes::disc(glm::vec2 centre, float radius, const glm::vec4& colour) {
    if (!(radius > 0)) return;
    add(Kind::disc, colour, {centre}).a = radius;
}

void Shapes::ring(glm::vec2 centre, float inner_radius, float outer_radius, const glm::vec4& colour) {
    inner_radius = std::max(0.0f, inner_radius);
    if (!(outer_radius > inner_radius)) return;
    Op& op = add(Kind::ring, colour, {centre});
    op.a = inner_radius;
    op.b = outer_radius;
}

void Shapes::convex_polygon(std::span<const glm::vec2> points, const glm::vec4& colour) {
    if (points.size() < 3) return;
    Op& op = add(Kind::polygon, colour, {});
    op.count = static_cast<std::uint32_t>(points.size());
    points_.insert(points_.end(), points.begin(), points.end());
}

void Shapes::polyline(std::span<const glm::vec2> points, float width, const glm::vec4& colour,
                      std::span<const float> dash, float dash_offset, LineCap cap) {
    if (!(width > 0) || points.size() < 2) return;
    Op& op = add(Kind::polyline, colour, {});
    op.count = static_cast<std::uint32_t>(points.size());
    op.width = width;
    op.cap = cap;
    op.b = dash_offset;
    op.dash_first = static_cast<std::uint32_t>(dashes_.size());
    op.dash_count = static_cast<std::uint32_t>(dash.size());
    points_.insert(points_.end(), points.begin(), points.end());
    dashes_.insert(dashes_.end(), dash.begin(), dash.end());
}

void Shapes::draw(Surface& surface) const {
    if (!ops_.empty()) surface.shapes(*this, Coverage::each);
}

// Triangulation, for the GL backend: each primitive into triangles, three
// vertices each.
namespace {

class Triangles {
public:
    explicit Triangles(std::vector<Shapes::Vertex>& out) : out_(out) {}

    void triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, const glm::vec4& colour) {
        out_.push_back({a, colour});
        out_.push_back({b, colour});
        out_.push_back({c, colour});
    }

    void rect(const Rect& r, const glm::vec4& colour) {
        const glm::vec2 tl{r.x, r.y}, tr{r.right(), r.y}, bl{r.x, r.bottom()}, br{r.right(), r.bottom()};
        triangle(tl, tr, br, colour);
        triangle(tl, br, bl, colour);
    }

    void frame(const Rect& r, float width, const glm::vec4& colour) {
        rect({r.x, r.y, r.w, width}, colour);                             // top
        rect({r.x, r.bottom() - width, r.w, width}, colour);              // bottom
        rect({r.x, r.y + width, width, r.h - 2 * width}, colour);         // left
        rect({r.right() - width, r.y + width, width, r.h - 2 * width}, colour);  // right
    }

    void line(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour) {
        const glm::vec2 d = b - a;
        const float length = glm::length(d);
        const glm::vec2 n = glm::vec2(-d.y, d.x) * (0.5f * width / length);
        triangle(a + n, b + n, b - n, colour);
        triangle(a + n, b - n, a - n, colour);
    }

    void disc(glm::vec2 centre, float radius, const glm::vec4& colour);
    void ring(glm::vec2 centre, float inner_radius, float outer_radius, const glm::vec4& colour);

    void convex_polygon(std::span<const glm::vec2> points, const glm::vec4& colour) {
        for (std::size_t i = 2; i < points.size(); ++i) triangle(points[0], points[i - 1], points[i], colour);
    }

    void polyline(std::span<const glm::vec2> points, float width, const glm::vec4& colour, std::span<const float> dash,
                  float dash_offset, LineCap cap);

private:
    void solid_polyline(std::span<const glm::vec2> points, float width, const glm::vec4& colour, LineCap cap);

    std::vector<Shapes::Vertex>& out_;
};

// Chords of about two pixels: finer than the 4x multisampling can show.
int disc_chords(float radius) { return std::clamp(int(std::ceil(std::numbers::pi_v<float> * radius)), 12, 96); }

void Triangles::disc(glm::vec2 centre, float radius, const glm::vec4& colour) {
    const int n = disc_chords(radius);
    glm::vec2 previous = centre + glm::vec2(radius, 0);
    for (int i = 1; i <= n; ++i) {
        const float a = 2 * std::numbers::pi_v<float> * float(i) / float(n);
        const glm::vec2 next = centre + radius * glm::vec2(std::cos(a), std::sin(a));
        triangle(centre, previous, next, colour);
        previous = next;
    }
}

void Triangles::ring(glm::vec2 centre, float inner_radius, float outer_radius, const glm::vec4& colour) {
    const int n = std::clamp(int(std::ceil(std::numbers::pi_v<float> * outer_radius)), 12, 96);
    for (int i = 0; i < n; ++i) {
        const float a0 = 2 * std::numbers::pi_v<float> * float(i) / float(n);
        const float a1 = 2 * std::numbers::pi_v<float> * float(i + 1) / float(n);
        const glm::vec2 u0{std::cos(a0), std::sin(a0)}, u1{std::cos(a1), std::sin(a1)};
        triangle(centre + inner_radius * u0, centre + outer_radius * u0, centre + outer_radius * u1, colour);
        triangle(centre + inner_radius * u0, centre + outer_radius * u1, centre + inner_radius * u1, colour);
    }
}

void Triangles::polyline(std::span<const glm::vec2> points, float width, const glm::vec4& colour,
                         std::span<const float> dash, float dash_offset, LineCap cap) {
    if (!(width > 0) || points.size() < 2) return;
    std::vector<float> pattern(dash.begin(), dash.end());
    if (pattern.size() % 2 == 1) pattern.insert(pattern.end(), dash.begin(), dash.end());
    float period = 0;
    for (float d : pattern) period += std::max(0.0f, d);
    if (pattern.empty() || !(period > 1e-3f)) return solid_polyline(points, width, colour, cap);

    // Where in the pattern the line starts: entry k with `left` pixels of it to go.
    float phase = std::fmod(dash_offset, period);
    if (phase < 0) phase += period;
    std::size_t k = 0;
    while (phase >= std::max(0.0f, pattern[k])) phase -= std::max(0.0f, pattern[k]), k = (k + 1) % pattern.size();
    float left = std::max(0.0f, pattern[k]) - phase;
    std::vector<glm::vec2> piece;
    if (k % 2 == 0) piece.push_back(points[0]);
    for (std::size_t i = 1; i < points.size(); ++i) {
        const glm::vec2 a = points[i - 1], b = points[i];
        const float length = glm::length(b - a);
        float done = 0;
        while (length - done > left) {  // the pattern switches inside this segment
            done += left;
            const glm::vec2 at = a + (b - a) * (done / length);
            if (k % 2 == 0) {
                piece.push_back(at);
                solid_polyline(piece, width, colour, cap);
                piece.clear();
            } else {
                piece.push_back(at);
            }
            k = (k + 1) % pattern.size();
            left = std::max(0.0f, pattern[k]);
        }
        left -= length - done;
        if (k % 2 == 0) piece.push_back(b);
    }
    if (k % 2 == 0) solid_polyline(piece, width, colour, cap);
}

void Triangles::solid_polyline(std::span<const glm::vec2> input, float width, const glm::vec4& colour,
                               LineCap cap) {
    std::vector<glm::vec2> p;  // without repeated points, which have no direction
    for (glm::vec2 q : input)
        if (p.empty() || glm::length(q - p.back()) > 1e-4f) p.push_back(q);
    if (p.size() < 2) return;
    const float h = width / 2;
    const std::size_t n = p.size();
    std::vector<glm::vec2> along(n - 1), normal(n - 1);
    std::vector<float> length(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) {
        length[i] = glm::length(p[i + 1] - p[i]);
        along[i] = (p[i + 1] - p[i]) / length[i];
        normal[i] = {-along[i].y, along[i].x};
    }
    auto quad = [&](glm::vec2 l0, glm::vec2 r0, glm::vec2 l1, glm::vec2 r1) {
        triangle(l0, l1, r1, colour);
        triangle(l0, r1, r0, colour);
    };
    const glm::vec2 start = cap == LineCap::square ? p[0] - along[0] * h : p[0];
    glm::vec2 left = start + normal[0] * h, right = start - normal[0] * h;
    for (std::size_t i = 1; i + 1 < n; ++i) {
        const glm::vec2 a = normal[i - 1], b = normal[i], sum = a + b;
        const float sum_length = glm::length(sum);
        if (sum_length > 1e-6f) {
            const glm::vec2 miter = sum / sum_length;
            const float c = glm::dot(miter, a);  // cosine of half the turn
            // A mitre, unless the turn is sharp or the inner corner would
            // reach past a neighbouring segment and fold the strip.
            const float reach = h * std::sqrt(std::max(0.0f, 1 - c * c)) / c;
            if (c >= 0.5f && reach <= std::min(length[i - 1], length[i])) {
                const glm::vec2 l = p[i] + miter * (h / c), r = p[i] - miter * (h / c);
                quad(left, right, l, r);
                left = l, right = r;
                continue;
            }
        }
        // Bevel, and a round fan over the outer corner.
        quad(left, right, p[i] + a * h, p[i] - a * h);
        const float side = glm::dot(along[i], a) > 0 ? -1.0f : 1.0f;  // the outer side of the turn
        const float from = std::atan2(side * a.y, side * a.x);
        float turn = std::atan2(side * b.y, side * b.x) - from;
        if (turn > std::numbers::pi_v<float>) turn -= 2 * std::numbers::pi_v<float>;
        if (turn < -std::numbers::pi_v<float>) turn += 2 * std::numbers::pi_v<float>;
        const int steps = std::max(1, int(std::ceil(std::abs(turn) / 0.3f)));
        glm::vec2 previous = p[i] + side * a * h;
        for (int s = 1; s <= steps; ++s) {
            const float angle = from + turn * float(s) / float(steps);
            const glm::vec2 next = p[i] + h * glm::vec2(std::cos(angle), std::sin(angle));
            triangle(p[i], previous, next, colour);
            previous = next;
        }
        left = p[i] + b * h, right = p[i] - b * h;
    }
    const glm::vec2 end = cap == LineCap::square ? p[n - 1] + along[n - 2] * h : p[n - 1];
    quad(left, right, end + normal[n - 2] * h, end - normal[n - 2] * h);
}

}  // namespace

std::size_t Shapes::disc_vertices(float radius) {
    return radius > 0 ? 3 * static_cast<std::size_t>(disc_chords(radius)) : 0;
}

void Shapes::tessellate(std::size_t first, std::size_t end, std::vector<Vertex>& out) const {
    Triangles t(out);
    for (std::size_t i = first; i < end; ++i) {
        const Op& op = ops_[i];
        const auto p = op.points(*this);
        switch (op.kind) {
            case Kind::triangle: t.triangle(p[0], p[1], p[2], op.colour); break;
            case Kind::rect: t.rect({p[0].x, p[0].y, p[1].x, p[1].y}, op.colour); break;
            case Kind::frame: t.frame({p[0].x, p[0].y, p[1].x, p[1].y}, op.width, op.colour); break;
            case Kind::line: t.line(p[0], p[1], op.width, op.colour); break;
            case Kind::round_segment:
                if (glm::length(p[1] - p[0]) != 0.0f) t.line(p[0], p[1], op.width, op.colour);
                t.disc(p[0], op.width / 2, op.colour);
                t.disc(p[1], op.width / 2, op.colour);
                break;
            case Kind::disc: t.disc(p[0], op.a, op.colour); break;
            case Kind::ring: t.ring(p[0], op.a, op.b, op.colour); break;
            case Kind::polygon: t.convex_polygon(p, op.colour); break;
            case Kind::polyline: t.polyline(p, op.width, op.colour, op.dash(*this), op.b, op.cap); break;
        }
    }
}

}  // namespace render
