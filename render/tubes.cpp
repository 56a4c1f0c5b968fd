#include "render/tubes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>


namespace render {
namespace {

struct PixelRect {
    int x, y, w, h;  // top-left origin, y down
};

PixelRect whole_pixels(const Rect& r) {
    const int x = int(std::lround(r.x)), y = int(std::lround(r.y));
    const PixelRect p{x, y, int(std::lround(r.right())) - x, int(std::lround(r.bottom())) - y};
    if (p.w < 1 || p.h < 1) throw std::invalid_argument("draw_tubes: the viewport is empty");
    return p;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::vector<Tube> box_edges(glm::vec3 lo, glm::vec3 hi, float radius, glm::vec4 colour) {
    std::vector<Tube> edges;
    for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 4; ++k) {
            glm::vec3 a, b;
            for (int i = 0, bit = 0; i < 3; ++i) {
                if (i == axis) {
                    a[i] = lo[i], b[i] = hi[i];
                } else {
                    a[i] = b[i] = (k >> bit & 1) ? hi[i] : lo[i];
                    ++bit;
                }
            }
            edges.push_back({a, b, radius, radius, colour});
        }
    return edges;
}

Camera frame_bounds(glm::vec3 lo, glm::vec3 hi, float azimuth_degrees, float elevation_degrees, float aspect,
                    float fov_degrees) {
    const float azimuth = glm::radians(azimuth_degrees), elevation = glm::radians(elevation_degrees);
    const glm::vec3 centre = (lo + hi) * 0.5f;
    // Towards the eye, and up on screen: the derivative of that direction in
    // elevation, so straight down still has an up.
    const glm::vec3 back{std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                         std::cos(elevation) * std::cos(azimuth)};
    const glm::vec3 up{-std::sin(elevation) * std::sin(azimuth), std::cos(elevation),
                       -std::sin(elevation) * std::cos(azimuth)};
    const glm::vec3 right = glm::cross(up, back);
    // The corners fill at most this share of the half-width or half-height.
    const float fill = 0.94f;
    const float tan_v = std::tan(glm::radians(fov_degrees) / 2) * fill, tan_h = tan_v * aspect;
    const float radius = glm::length(hi - lo) / 2;
    // A corner at (x, y) across and z towards the eye fits when
    // |x| <= (distance - z) tan_h and |y| <= (distance - z) tan_v.
    float distance = 0;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner{i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
        const glm::vec3 q = corner - centre;
        const float z = glm::dot(q, back);
        distance = std::max({distance, z + std::abs(glm::dot(q, right)) / tan_h, z + std::abs(glm::dot(q, up)) / tan_v});
    }
    // Outside the box's sphere, so near stays positive; a point gets a unit distance.
    distance = radius > 0 ? std::max(distance, 1.05f * radius) : 1.0f;
    Camera camera;
    camera.eye = centre + distance * back;
    camera.target = centre;
    camera.up = up;
    camera.fov_degrees = fov_degrees;
    camera.near = std::max(distance - radius, 1e-3f * distance) * 0.9f;
    camera.far = (distance + radius) * 1.1f;
    return camera;
}

std::pair<glm::vec3, glm::vec3> tube_bounds(const std::vector<Tube>& tubes) {
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const Tube& t : tubes) {
        lo = glm::min(lo, glm::min(t.a - t.radius_a, t.b - t.radius_b));
        hi = glm::max(hi, glm::max(t.a + t.radius_a, t.b + t.radius_b));
    }
    if (tubes.empty()) lo = hi = glm::vec3(0);
    return {lo, hi};
}

std::vector<Ball> balls_of(const std::vector<Tube>& tubes, const std::vector<Facet>& facets) {
    std::vector<Ball> balls;
    balls.reserve(2 * tubes.size() + 3 * facets.size());
    for (const Tube& t : tubes) balls.insert(balls.end(), {{t.a, t.radius_a}, {t.b, t.radius_b}});
    for (const Facet& f : facets) balls.insert(balls.end(), {{f.a, 0}, {f.b, 0}, {f.c, 0}});
    return balls;
}

namespace {

// The camera's axes for a direction, as frame_bounds takes them: towards the
// eye, up on screen (the derivative of `back` in elevation, so straight down
// still has an up) and right.
struct Axes {
    glm::vec3 back, up, right;
};

Axes axes_of(float azimuth_degrees, float elevation_degrees) {
    const float azimuth = glm::radians(azimuth_degrees), elevation = glm::radians(elevation_degrees);
    Axes axes;
    axes.back = {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
    axes.up = {-std::sin(elevation) * std::sin(azimuth), std::cos(elevation), -std::sin(elevation) * std::cos(azimuth)};
    axes.right = glm::cross(axes.up, axes.back);
    return axes;
}

// The extent in tangents of the view angle, (x, y) / depth, of balls seen
// from target + distance * back; doubles, as the balls may be many.
Extent tangent_extent(std::span<const Ball> balls, const Axes& axes, glm::vec3 target, double distance) {
    const double inf = std::numeric_limits<double>::infinity();
    glm::dvec2 lo(inf), hi(-inf);
    for (const Ball& b : balls) {
        const glm::dvec3 q = glm::dvec3(b.centre) - glm::dvec3(target);
        const double depth = distance - glm::dot(q, glm::dvec3(axes.back));
        const glm::dvec2 at{glm::dot(q, glm::dvec3(axes.right)), glm::dot(q, glm::dvec3(axes.up))};
        lo = glm::min(lo, (at - double(b.radius)) / depth);
        hi = glm::max(hi, (at + double(b.radius)) / depth);
    }
    return {glm::vec2(lo), glm::vec2(hi)};
}

}  // namespace

Extent projected_extent(std::span<const Ball> balls, const Camera& camera, float aspect) {
    // Only the projection matters here: the axes from the camera itself.
    const glm::vec3 back = glm::normalize(camera.eye - camera.target);
    const glm::vec3 right = glm::normalize(glm::cross(camera.up, back));
    const Axes axes{back, glm::cross(back, right), right};
    const Extent t = tangent_extent(balls, axes, camera.target, glm::length(camera.eye - camera.target));
    const float tan_v = std::tan(glm::radians(camera.fov_degrees) / 2);
    const glm::vec2 scale{tan_v * aspect, tan_v};
    return {t.lo / scale, t.hi / scale};
}

Camera frame_balls(std::span<const Ball> balls, float azimuth_degrees, float elevation_degrees, float aspect,
                   float fill, float min_distance, float fov_degrees) {
    const Axes axes = axes_of(azimuth_degrees, elevation_degrees);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Ball& b : balls) {
        lo = glm::min(lo, glm::dvec3(b.centre) - double(b.radius));
        hi = glm::max(hi, glm::dvec3(b.centre) + double(b.radius));
    }
    if (balls.empty()) lo = hi = glm::dvec3(0);
    glm::dvec3 target = (lo + hi) * 0.5;
    const double reach = glm::length(hi - lo) / 2;  // every ball lies within this of the box's centre
    const double tan_v = std::tan(glm::radians(double(fov_degrees)) / 2), tan_h = tan_v * aspect;
    const glm::dvec3 back(axes.back), up(axes.up), right(axes.right);
    double distance = 1;
    // Fit, centre, fit again: a shift across the line of sight moves every
    // ball's image alike but for perspective, so a few rounds settle it.
    constexpr int rounds = 8;
    for (int round = 0; round < rounds; ++round) {
        // The distance at which the widest ball reaches `fill` of the half-width or half-height.
        distance = std::max(double(min_distance), 1e-6);
        for (const Ball& b : balls) {
            const glm::dvec3 q = glm::dvec3(b.centre) - target;
            const double z = glm::dot(q, back), r = b.radius;
            distance = std::max({distance, z + (std::abs(glm::dot(q, right)) + r) / (fill * tan_h),
                                 z + (std::abs(glm::dot(q, up)) + r) / (fill * tan_v)});
        }
        // Outside every ball, so that near stays positive.
        distance = reach > 0 ? std::max(distance, 1.05 * (reach + glm::length(target - (lo + hi) * 0.5)))
                             : std::max(distance, 1.0);
        if (round == rounds - 1) break;
        const Extent t = tangent_extent(balls, axes, glm::vec3(target), distance);
        const glm::dvec2 middle = (glm::dvec2(t.lo) + glm::dvec2(t.hi)) * 0.5;
        target += distance * (middle.x * right + middle.y * up);
    }
    const double radius = reach + glm::length(target - (lo + hi) * 0.5);  // of a sphere about target holding all
    Camera camera;
    camera.target = glm::vec3(target);
    camera.eye = glm::vec3(target + distance * back);
    camera.up = axes.up;
    camera.fov_degrees = fov_degrees;
    camera.near = float(std::max(distance - radius, 1e-3 * distance) * 0.9);
    camera.far = float((distance + radius) * 1.1);
    return camera;
}

glm::mat4 view_projection(const Camera& camera, float aspect) {
    return glm::perspective(glm::radians(camera.fov_degrees), aspect, camera.near, camera.far) *
           glm::lookAt(camera.eye, camera.target, camera.up);
}

glm::vec2 project(const Camera& camera, const Rect& viewport, glm::vec3 point) {
    const PixelRect p = whole_pixels(viewport);
    const glm::vec4 clip = view_projection(camera, float(p.w) / float(p.h)) * glm::vec4(point, 1);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {float(p.x) + (ndc.x + 1) / 2 * float(p.w), float(p.y) + (1 - ndc.y) / 2 * float(p.h)};
}

void draw_tubes(Surface& surface, const Rect& viewport, const std::vector<Tube>& tubes,
                const std::vector<Facet>& facets, const Camera& camera, const Light& light, int sides) {
    if (sides < 3 || sides > 256) throw std::invalid_argument("draw_tubes: sides must be 3..256");
    for (const Tube& t : tubes)
        if (!(t.radius_a >= 0 && t.radius_b >= 0 && std::isfinite(t.radius_a) && std::isfinite(t.radius_b) &&
              finite(t.a) && finite(t.b)))
            throw std::invalid_argument("draw_tubes: a tube has a negative or non-finite radius or end point");
    for (const Facet& f : facets)
        if (!(finite(f.a) && finite(f.b) && finite(f.c)))
            throw std::invalid_argument("draw_tubes: a facet has a non-finite corner");
    whole_pixels(viewport);  // refuses an empty one
    surface.tubes(viewport, tubes, facets, camera, light, sides);
}

void draw_tubes(Surface& surface, const Rect& viewport, const std::vector<Tube>& tubes, const Camera& camera,
                const Light& light, int sides) {
    draw_tubes(surface, viewport, tubes, {}, camera, light, sides);
}

}  // namespace render
