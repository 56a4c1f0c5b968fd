// The GL canvas's hexagonal cells (render/hex_cells.hpp): one instanced
// hexagon per cell, its corners from exact lattice offsets.
#include <algorithm>
#include <cstddef>

#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/program.hpp"
#include "render/hex_cells.hpp"

namespace render {
namespace {

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

}  // namespace render
