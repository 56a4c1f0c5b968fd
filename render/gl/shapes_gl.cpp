// The GL canvas's shapes (render/shapes.hpp): triangles in batches.
#include <cstddef>
#include <vector>

#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/program.hpp"
#include "render/shapes.hpp"

namespace render {
namespace {

const char* const vertex_shader = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec4 colour;
uniform mat4 projection;
out vec4 v_colour;
void main() {
    v_colour = colour;
    gl_Position = projection * vec4(position, 0.0, 1.0);
})";

const char* const fragment_shader = R"(#version 330 core
in vec4 v_colour;
out vec4 out_colour;
void main() { out_colour = v_colour; })";

// Shared by every batch of this kind, created on first use.
StreamPipeline& pipeline() {
    static StreamPipeline p{vertex_shader, fragment_shader};
    return p;
}

}  // namespace

namespace gl_backend {

// Triangulates the primitives into batches of about triangles_per_finish
// triangles, uploading and drawing each and finishing it before the next:
// what the GL holds at once is one batch, whatever the number of shapes.
void shapes(const Canvas& canvas, const Shapes& shapes) {
    StreamPipeline& p = pipeline();
    canvas.bind();
    p.program.use();
    p.program.set("projection", canvas.projection());
    glBindVertexArray(p.vao);
    glBindBuffer(GL_ARRAY_BUFFER, p.vbo);
    std::vector<Shapes::Vertex> batch;
    const std::size_t batch_vertices = 3 * static_cast<std::size_t>(triangles_per_finish);
    const std::size_t count = shapes.ops().size();
    bool drawn = false;
    for (std::size_t first = 0; first < count;) {
        batch.clear();
        std::size_t end = first;
        while (end < count && batch.size() < batch_vertices) shapes.tessellate(end, end + 1, batch), ++end;
        first = end;
        if (batch.empty()) continue;
        if (drawn) glFinish();  // see triangles_per_finish
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(batch.size() * sizeof(Shapes::Vertex)), batch.data(),
                     GL_STREAM_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Shapes::Vertex),
                              reinterpret_cast<const void*>(offsetof(Shapes::Vertex, position)));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Shapes::Vertex),
                              reinterpret_cast<const void*>(offsetof(Shapes::Vertex, colour)));
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(batch.size()));
        drawn = true;
    }
    glBindVertexArray(0);
    check_gl("Shapes::draw");
}

}  // namespace gl_backend
}  // namespace render
