#pragma once
// Flat-coloured geometry (rectangles, frames, line segments) collected into
// one vertex batch and drawn with a single draw call.

#include <vector>

#include <glm/glm.hpp>

#include "render/canvas.hpp"

namespace render {

class Shapes {
public:
    void rect(const Rect& r, const glm::vec4& colour);
    // The outline of r, `width` pixels wide, drawn inside r's edges.
    void frame(const Rect& r, float width, const glm::vec4& colour);
    // A segment `width` pixels wide with square (butt) ends.
    void line(glm::vec2 a, glm::vec2 b, float width, const glm::vec4& colour);
    void triangle(glm::vec2 a, glm::vec2 b, glm::vec2 c, const glm::vec4& colour);

    bool empty() const { return vertices_.empty(); }
    void clear() { vertices_.clear(); }
    void draw(const Canvas& canvas) const;

private:
    struct Vertex {
        glm::vec2 position;
        glm::vec4 colour;
    };
    std::vector<Vertex> vertices_;
};

}  // namespace render
