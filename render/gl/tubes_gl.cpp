// The GL canvas's tubes and facets (render/tubes.hpp): instanced capsules
// and flat triangles, lit and depth-tested.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/program.hpp"
#include "render/tubes.hpp"

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

// A facet's corner as GL reads it: the facet's normal, the same at each
// corner, or the surface's own at the corner when the facet gives it.
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
            auto normal = [&](const glm::vec3& given) {
                const float length = glm::length(given);
                return length > 0 && std::isfinite(length) ? given / length : n;
            };
            corners.push_back({f.a, normal(f.na), f.colour});
            corners.push_back({f.b, normal(f.nb), f.colour});
            corners.push_back({f.c, normal(f.nc), f.colour});
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

}  // namespace

void gl_backend::tubes(const Canvas& canvas, const Rect& viewport, const std::vector<Tube>& tubes,
                       const std::vector<Facet>& facets, const Camera& camera, const Light& light, int sides) {
    if (!canvas.has_depth())
        throw std::logic_error("draw_tubes: the canvas has no depth buffer (make it with depth = true)");
    const PixelBox box = clip_box(viewport);  // draw_tubes refused an empty one
    const struct {
        int x, y, w, h;
    } p{box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0};
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
