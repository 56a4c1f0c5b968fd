#include "render/hex_cells.hpp"

#include "render/gl_backend.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/gl_context.hpp"
#include "render/program.hpp"

namespace render {
namespace {

const float sqrt3 = std::sqrt(3.0f);

const char* const vertex_shader = R"(#version 330 core
// One hexagon per instance: four triangles fanned from corner 0, corners
// at 0, 60, ..., 300 degrees (flat top).
layout(location = 0) in ivec2 cell;
uniform mat4 projection;
uniform vec2 centre;
uniform float size;
void main() {
    const int corner_of[12] = int[12](0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5);
    // Corners in units of half the size, from the cell's centre, as exact
    // lattice offsets: neighbours then compute their shared corners from the
    // same integers, and no seam opens between them.
    const vec2 corner[6] = vec2[6](vec2(2.0, 0.0), vec2(1.0, 1.0), vec2(-1.0, 1.0), vec2(-2.0, 0.0),
                                   vec2(-1.0, -1.0), vec2(1.0, -1.0));
    vec2 c = corner[corner_of[gl_VertexID]];
    // In half-sizes: x = 3 q + c.x; y (up) = sqrt(3) (2 r + q + c.y).
    vec2 half_units = vec2(3.0 * float(cell.x) + c.x, -(2.0 * float(cell.y) + float(cell.x) + c.y));
    gl_Position = projection * vec4(centre + 0.5 * size * vec2(half_units.x, sqrt(3.0) * half_units.y), 0.0, 1.0);
})";

const char* const fragment_shader = R"(#version 330 core
uniform vec4 colour;
out vec4 out_colour;
void main() { out_colour = colour; })";

}  // namespace

HexView fit_hex_view(const Rect& area, int radius) {
    const float r = float(std::max(radius, 0));
    // Half-extents of the cells within distance r: 1.5 r + 1 sizes across,
    // sqrt(3) (r + 1/2) sizes up and down.
    const float size = std::min(area.w / 2 / (1.5f * r + 1), area.h / 2 / (sqrt3 * (r + 0.5f)));
    return {area.centre(), size};
}

glm::vec2 hex_centre(const HexView& view, glm::ivec2 cell) {
    return view.centre + view.size * glm::vec2(1.5f * float(cell.x), -sqrt3 * (float(cell.y) + 0.5f * float(cell.x)));
}

void draw_hex_cells(Surface& surface, const HexView& view, const std::vector<glm::ivec2>& cells,
                    const glm::vec4& colour) {
    if (!cells.empty()) surface.hex_cells(view, cells, colour);
}

void gl_backend::hex_cells(const Canvas& canvas, const HexView& view, std::span<const glm::ivec2> cells,
                           const glm::vec4& colour) {
    static StreamPipeline p{vertex_shader, fragment_shader};
    canvas.bind();
    p.program.use();
    p.program.set("projection", canvas.projection());
    p.program.set("centre", view.centre);
    p.program.set("size", view.size);
    p.program.set("colour", colour);
    glBindVertexArray(p.vao);
    glBindBuffer(GL_ARRAY_BUFFER, p.vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(cells.size() * sizeof(glm::ivec2)), cells.data(),
                 GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribDivisor(0, 1);
    // Batches of cells (4 triangles each), finishing each: see triangles_per_finish.
    // Each batch points the attribute at its first cell (GL 3.3; a
    // base-instance draw would need GL 4.2).
    const long long total = static_cast<long long>(cells.size()), batch = triangles_per_finish / 4;
    for (long long first = 0; first < total; first += batch) {
        if (first > 0) glFinish();
        glVertexAttribIPointer(0, 2, GL_INT, sizeof(glm::ivec2),
                               reinterpret_cast<const void*>(static_cast<std::size_t>(first) * sizeof(glm::ivec2)));
        glDrawArraysInstanced(GL_TRIANGLES, 0, 12, static_cast<GLsizei>(std::min(batch, total - first)));
    }
    glVertexAttribDivisor(0, 0);
    glBindVertexArray(0);
    check_gl("draw_hex_cells");
}

void hex_outline(Shapes& shapes, const HexView& view, glm::ivec2 cell, float width, const glm::vec4& colour) {
    const glm::vec2 c = hex_centre(view, cell);
    // Around once and one corner further, so corner 0 gets a mitred joint too.
    std::array<glm::vec2, 8> corners;
    for (int k = 0; k < 8; ++k) {
        const float angle = glm::radians(60.0f * float(k % 6));
        corners[k] = c + view.size * glm::vec2(std::cos(angle), std::sin(angle));
    }
    shapes.polyline(corners, width, colour);
}

}  // namespace render
