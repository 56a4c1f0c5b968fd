#include "render/tubes.hpp"

#include "render/gl_backend.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gl_context.hpp"
#include "render/program.hpp"

namespace render {
namespace {

// The tubes go to GL as they are: one instance each, no copy.
static_assert(sizeof(Tube) == 12 * sizeof(float));
static_assert(offsetof(Tube, radius_b) == offsetof(Tube, radius_a) + sizeof(float));

const char* const vertex_shader = R"(#version 330 core
// One capsule per instance. The mesh is in the tube's own frame: (x, y) across
// the axis and h along it, in radii, from the end point `end` (0: a, 1: b).
layout(location = 0) in vec3 local;
layout(location = 1) in float end;
layout(location = 2) in float on_cap;  // 1 on the round ends, 0 on the cone
layout(location = 3) in vec3 a;
layout(location = 4) in vec3 b;
layout(location = 5) in vec2 radii;
layout(location = 6) in vec4 colour;
uniform mat4 view_projection;
out vec3 v_position;
centroid out vec3 v_normal;  // centroid: edge pixels do not extrapolate the normal off the surface
flat out vec4 v_colour;
void main() {
    float len = length(b - a);
    vec3 d = len > 0.0 ? (b - a) / len : vec3(0.0, 1.0, 0.0);
    // Any frame about the axis will do: the mesh is round.
    vec3 u = normalize(cross(abs(d.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), d));
    vec3 v = cross(d, u);
    float r = mix(radii.x, radii.y, end);
    vec3 radial = local.x * u + local.y * v;
    v_position = mix(a, b, end) + r * (radial + local.z * d);
    // A cone's normal leans towards its thin end by the slope (r_b - r_a) / length.
    vec3 side = len > 0.0 ? radial * len - (radii.y - radii.x) * d : radial;
    v_normal = on_cap > 0.5 ? radial + local.z * d : side;
    v_colour = colour;
    gl_Position = view_projection * vec4(v_position, 1.0);
})";

const char* const fragment_shader = R"(#version 330 core
in vec3 v_position;
centroid in vec3 v_normal;
flat in vec4 v_colour;
uniform vec3 eye;
uniform vec3 light_direction;  // unit, towards the light
uniform vec3 light;            // ambient, diffuse, specular
out vec4 out_colour;
void main() {
    // A facet is lit on the side the eye sees; a tube's back faces are culled, so this never flips one.
    vec3 n = normalize(gl_FrontFacing ? v_normal : -v_normal);
    vec3 to_eye = normalize(eye - v_position);
    float lambert = max(dot(n, light_direction), 0.0);
    // Blinn-Phong: a highlight where the normal halves light and eye; none on the dark side.
    float highlight = lambert > 0.0 ? pow(max(dot(n, normalize(light_direction + to_eye)), 0.0), 32.0) : 0.0;
    vec3 lit = v_colour.rgb * (light.x + light.y * lambert) + light.z * highlight;
    out_colour = vec4(min(lit, vec3(1.0)), v_colour.a);
})";

const char* const facet_vertex_shader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 colour;
uniform mat4 view_projection;
out vec3 v_position;
centroid out vec3 v_normal;
flat out vec4 v_colour;
void main() {
    v_position = position;
    v_normal = normal;
    v_colour = colour;
    gl_Position = view_projection * vec4(position, 1.0);
})";

// A facet's corner as GL reads it: the facet's normal, the same at each corner.
struct FacetVertex {
    glm::vec3 position, normal;
    glm::vec4 colour;
};

struct MeshVertex {
    glm::vec3 local;  // across the axis (x, y) and along it (h), in radii
    float end;        // 0: at a, 1: at b
    float on_cap;     // 1: on a round end, 0: on the cone
};

struct Mesh {
    std::vector<MeshVertex> vertices;
    std::vector<GLuint> indices;
};

// The unit capsule: a cone of `sides` facets and a hemisphere over each end,
// bands of the same angle as the facets. Cone and hemisphere share their rim
// positions bit for bit (the same sines and cosines), so no crack opens there.
Mesh capsule_mesh(int sides) {
    Mesh mesh;
    std::vector<glm::vec2> rim(static_cast<std::size_t>(sides));
    for (int k = 0; k < sides; ++k) {
        const double angle = 2 * std::numbers::pi * k / sides;
        rim[k] = {float(std::cos(angle)), float(std::sin(angle))};
    }
    // Each triangle turned so that its front faces out; with culling on only
    // the near side is shaded. The mapping to world keeps orientation: the
    // frame (u, v, d) is right-handed and the radii are positive.
    auto triangle = [&](GLuint i, GLuint j, GLuint k, glm::vec3 outward) {
        auto at = [&](GLuint n) {
            const MeshVertex& m = mesh.vertices[n];
            return m.on_cap > 0.5f ? m.local : glm::vec3(m.local.x, m.local.y, m.end);
        };
        if (glm::dot(glm::cross(at(j) - at(i), at(k) - at(i)), outward) < 0) std::swap(j, k);
        mesh.indices.insert(mesh.indices.end(), {i, j, k});
    };
    auto ring = [&](float end, float on_cap, float across, float along) {
        const auto first = GLuint(mesh.vertices.size());
        for (glm::vec2 p : rim) mesh.vertices.push_back({{across * p.x, across * p.y, along}, end, on_cap});
        return first;
    };
    auto band = [&](GLuint lower, GLuint upper, glm::vec3 outward_axis) {
        for (int k = 0; k < sides; ++k) {
            const auto k1 = GLuint((k + 1) % sides);
            const glm::vec3 out = glm::vec3(rim[k], 0) + outward_axis;
            triangle(lower + GLuint(k), lower + k1, upper + k1, out);
            triangle(lower + GLuint(k), upper + k1, upper + GLuint(k), out);
        }
    };
    band(ring(0, 0, 1, 0), ring(1, 0, 1, 0), {0, 0, 0});  // the cone
    const int bands = std::max(1, sides / 4);
    for (float end : {0.0f, 1.0f}) {
        const float out = end > 0 ? 1.0f : -1.0f;  // the cap at a bulges back along the axis
        GLuint lower = ring(end, 1, 1, 0);
        for (int j = 1; j < bands; ++j) {
            const double latitude = std::numbers::pi / 2 * j / bands;
            const GLuint upper = ring(end, 1, float(std::cos(latitude)), out * float(std::sin(latitude)));
            band(lower, upper, {0, 0, out});
            lower = upper;
        }
        const auto pole = GLuint(mesh.vertices.size());
        mesh.vertices.push_back({{0, 0, out}, end, 1});
        for (int k = 0; k < sides; ++k)
            triangle(lower + GLuint(k), lower + GLuint((k + 1) % sides), pole, glm::vec3(rim[k], out));
    }
    return mesh;
}

// Lives as long as the context; the mesh is rebuilt when `sides` changes.
struct TubePipeline {
    Program program{vertex_shader, fragment_shader};
    GLuint vao = 0, mesh_vbo = 0, mesh_ibo = 0, instance_vbo = 0;
    int sides = 0;
    GLsizei index_count = 0;

    TubePipeline() {
        glGenVertexArrays(1, &vao);
        GLuint buffers[3];
        glGenBuffers(3, buffers);
        mesh_vbo = buffers[0], mesh_ibo = buffers[1], instance_vbo = buffers[2];
    }

    void use_mesh(int n) {
        if (n == sides) return;
        const Mesh mesh = capsule_mesh(n);
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof(MeshVertex)), mesh.vertices.data(),
                     GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                              reinterpret_cast<const void*>(offsetof(MeshVertex, local)));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                              reinterpret_cast<const void*>(offsetof(MeshVertex, end)));
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                              reinterpret_cast<const void*>(offsetof(MeshVertex, on_cap)));
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh_ibo);  // recorded in the vertex array
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(GLuint)), mesh.indices.data(),
                     GL_STATIC_DRAW);
        index_count = GLsizei(mesh.indices.size());
        sides = n;
    }

    void upload(const std::vector<Tube>& tubes) const {
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, instance_vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(tubes.size() * sizeof(Tube)), tubes.data(), GL_STREAM_DRAW);
        point_at(0);
    }

    // The per-tube attributes read from tube `first` on: a batch's first
    // instance. GL 4.2's base-instance draws would do it in the draw call;
    // moving the pointers keeps figgen on GL 3.3, all NVIDIA gives a 3.3
    // context. With the VAO and instance_vbo bound.
    void point_at(long long first) const {
        auto per_tube = [first](GLuint location, GLint size, std::size_t offset) {
            glEnableVertexAttribArray(location);
            glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, sizeof(Tube),
                                  reinterpret_cast<const void*>(std::size_t(first) * sizeof(Tube) + offset));
            glVertexAttribDivisor(location, 1);
        };
        per_tube(3, 3, offsetof(Tube, a));
        per_tube(4, 3, offsetof(Tube, b));
        per_tube(5, 2, offsetof(Tube, radius_a));
        per_tube(6, 4, offsetof(Tube, colour));
    }
};

// Lives as long as the context, beside the tubes' (the same fragment shader).
struct FacetPipeline {
    Program program{facet_vertex_shader, fragment_shader};
    GLuint vao = 0, vbo = 0;

    FacetPipeline() {
        glGenVertexArrays(1, &vao);
        glGenBuffers(1, &vbo);
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(FacetVertex),
                              reinterpret_cast<const void*>(offsetof(FacetVertex, position)));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(FacetVertex),
                              reinterpret_cast<const void*>(offsetof(FacetVertex, normal)));
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(FacetVertex),
                              reinterpret_cast<const void*>(offsetof(FacetVertex, colour)));
        glBindVertexArray(0);
    }

    // The facets with an area, three corners each; returns how many corners.
    GLsizei upload(const std::vector<Facet>& facets) const {
        std::vector<FacetVertex> corners;
        corners.reserve(3 * facets.size());
        for (const Facet& f : facets) {
            const glm::vec3 across = glm::cross(f.b - f.a, f.c - f.a);
            const float area = glm::length(across);
            if (!(area > 0) || !std::isfinite(area)) continue;  // no normal to light it by
            const glm::vec3 n = across / area;
            for (const glm::vec3& p : {f.a, f.b, f.c}) corners.push_back({p, n, f.colour});
        }
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners.size() * sizeof(FacetVertex)), corners.data(),
                     GL_STREAM_DRAW);
        return GLsizei(corners.size());
    }
};

void set_lighting(const Program& program, const Camera& camera, const Light& light, float aspect) {
    program.use();
    program.set("view_projection", view_projection(camera, aspect));
    glUniform3f(program.uniform("eye"), camera.eye.x, camera.eye.y, camera.eye.z);
    const glm::vec3 towards_light = glm::length(light.direction) > 0 ? glm::normalize(light.direction)
                                                                      : glm::vec3(0, 1, 0);
    glUniform3f(program.uniform("light_direction"), towards_light.x, towards_light.y, towards_light.z);
    glUniform3f(program.uniform("light"), light.ambient, light.diffuse, light.specular);
}

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

void gl_backend::tubes(const Canvas& canvas, const Rect& viewport, const std::vector<Tube>& tubes,
                       const std::vector<Facet>& facets, const Camera& camera, const Light& light, int sides) {
    if (!canvas.has_depth())
        throw std::logic_error("draw_tubes: the canvas has no depth buffer (make it with depth = true)");
    const PixelRect p = whole_pixels(viewport);
    static TubePipeline pipeline;
    canvas.bind();
    // GL counts rows from the bottom.
    glViewport(p.x, canvas.height() - p.y - p.h, p.w, p.h);
    glScissor(p.x, canvas.height() - p.y - p.h, p.w, p.h);
    glEnable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    if (!tubes.empty()) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glEnable(GL_CULL_FACE);  // capsules are closed: their back halves are never seen
        glCullFace(GL_BACK);
        glFrontFace(GL_CCW);
        pipeline.use_mesh(sides);
        pipeline.upload(tubes);
        set_lighting(pipeline.program, camera, light, float(p.w) / float(p.h));
        // Batches of tubes, finishing each: see triangles_per_finish.
        const long long total = static_cast<long long>(tubes.size());
        const long long batch = std::max(1LL, triangles_per_finish / (pipeline.index_count / 3));
        for (long long first = 0; first < total; first += batch) {
            if (first > 0) glFinish();
            pipeline.point_at(first);
            glDrawElementsInstanced(GL_TRIANGLES, pipeline.index_count, GL_UNSIGNED_INT, nullptr,
                                    GLsizei(std::min(batch, total - first)));
        }
        glBindVertexArray(0);
    }
    if (!facets.empty()) {
        static FacetPipeline facet_pipeline;
        if (!tubes.empty()) glFinish();  // one batch queued at a time, tubes' or facets'
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);  // a leaf is seen from both sides
        const GLsizei corners = facet_pipeline.upload(facets);
        set_lighting(facet_pipeline.program, camera, light, float(p.w) / float(p.h));
        glBindVertexArray(facet_pipeline.vao);
        // Batches, finishing each: see triangles_per_finish.
        const GLsizei batch = GLsizei(3 * triangles_per_finish);
        for (GLsizei first = 0; first < corners; first += batch) {
            if (first > 0) glFinish();
            glDrawArrays(GL_TRIANGLES, first, std::min(batch, corners - first));
        }
        glBindVertexArray(0);
    }
    // Back to what 2-D drawing expects.
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    canvas.bind();
    check_gl("draw_tubes");
}

}  // namespace render
