#include "render/shapes.hpp"

#include <cstddef>

#include "render/gl_context.hpp"
#include "render/program.hpp"

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

void Shapes::triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, const glm::vec4& colour) {
    vertices_.push_back({a, colour});
    vertices_.push_back({b, colour});
    vertices_.push_back({c, colour});
}

void Shapes::rect(const Rect& r, const glm::vec4& colour) {
    const glm::vec2 tl{r.x, r.y}, tr{r.right(), r.y}, bl{r.x, r.bottom()}, br{r.right(), r.bottom()};
    triangle(tl, tr, br, colour);
    triangle(tl, br, bl, colour);
}

void Shapes::frame(const Rect& r, float width, const glm::vec4& colour) {
    rect({r.x, r.y, r.w, width}, colour);                             // top
    rect({r.x, r.bottom() - width, r.w, width}, colour);              // bottom
    rect({r.x, r.y + width, width, r.h - 2 * width}, colour);         // left
    rect({r.right() - width, r.y + width, width, r.h - 2 * width}, colour);  // right
}

void Shapes::line(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour) {
    const glm::vec2 d = b - a;
    const float length = glm::length(d);
    if (length == 0.0f) return;
    const glm::vec2 n = glm::vec2(-d.y, d.x) * (0.5f * width / length);
    triangle(a + n, b + n, b - n, colour);
    triangle(a + n, b - n, a - n, colour);
}

void Shapes::draw(const Canvas& canvas) const {
    if (vertices_.empty()) return;
    StreamPipeline& p = pipeline();
    canvas.bind();
    p.program.use();
    p.program.set("projection", canvas.projection());
    glBindVertexArray(p.vao);
    glBindBuffer(GL_ARRAY_BUFFER, p.vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(Vertex)), vertices_.data(),
                 GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, colour)));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));
    glBindVertexArray(0);
    check_gl("Shapes::draw");
}

}  // namespace render
