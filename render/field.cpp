#include "render/field.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/program.hpp"

namespace render {
namespace {

const char* const vertex_shader = R"(#version 330 core
// One quad covering the field's rectangle, with field coordinates per corner.
uniform mat4 projection;
uniform vec4 rect;       // x, y, w, h in pixels
uniform vec2 cells;      // cols, rows
out vec2 field_position; // (col, row) in cell units, 0 at the top-left corner
void main() {
    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
    field_position = corner * cells;
    gl_Position = projection * vec4(rect.xy + corner * rect.zw, 0.0, 1.0);
})";

const char* const fragment_shader = R"(#version 330 core
in vec2 field_position;
out vec4 out_colour;
uniform sampler2D field;     // R32F, texel (col, row): (value - vmin) / (vmax - vmin)
uniform sampler2D colormap;  // 256 x 1 RGBA32F
uniform float alpha;
uniform int smooth_sampling;

float cell(ivec2 p) {
    ivec2 size = textureSize(field, 0);
    return texelFetch(field, clamp(p, ivec2(0), size - 1), 0).r;  // edge cells repeat, as Agg clamps
}

// Cubic B-spline weights for fractional offset t (Agg's image_filter_bicubic).
vec4 bspline(float t) {
    float s = 1.0 - t;
    return vec4(s * s * s, 4.0 - 6.0 * t * t + 3.0 * t * t * t,
                4.0 - 6.0 * s * s + 3.0 * s * s * s, t * t * t) / 6.0;
}

float sample_field() {
    if (smooth_sampling == 0) return cell(ivec2(floor(field_position)));
    // Cell centres sit at half-integers.
    vec2 p = field_position - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 t = p - vec2(base);
    vec4 wx = bspline(t.x), wy = bspline(t.y);
    float value = 0.0;
    for (int j = 0; j < 4; ++j) {
        float row = 0.0;
        for (int i = 0; i < 4; ++i) row += wx[i] * cell(base + ivec2(i - 1, j - 1));
        value += wy[j] * row;
    }
    return value;
}

void main() {
    float t = sample_field();
    // matplotlib's lookup: index floor(t * 256) clipped to 0..255.
    int index = clamp(int(floor(t * 256.0)), 0, 255);
    out_colour = vec4(texelFetch(colormap, ivec2(index, 0), 0).rgb, alpha);
})";

struct Pipeline {
    Program program{vertex_shader, fragment_shader};
    GLuint vao = 0, field_texture = 0, colormap_texture = 0;
    Pipeline() {
        glGenVertexArrays(1, &vao);
        glGenTextures(1, &field_texture);
        glGenTextures(1, &colormap_texture);
        for (GLuint texture : {field_texture, colormap_texture}) {
            glBindTexture(GL_TEXTURE_2D, texture);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
    }
};

Pipeline& pipeline() {
    static Pipeline p;
    return p;
}

}  // namespace

void draw_field(const Canvas& canvas, const Rect& where, int rows, int cols, std::span<const double> values,
                const FieldStyle& style) {
    if (rows < 1 || cols < 1 || values.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols))
        throw std::invalid_argument("draw_field: " + std::to_string(values.size()) + " values do not fill " +
                                    std::to_string(rows) + "x" + std::to_string(cols) + " cells");
    if (!style.colormap) throw std::invalid_argument("draw_field: no colormap");
    if (!(style.vmax > style.vmin))
        throw std::invalid_argument("draw_field: vmax must exceed vmin");
    Pipeline& p = pipeline();
    canvas.bind();

    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, p.colormap_texture);
    {  // 256 texels: cheaper to send each time than to track which map is loaded
        std::vector<float> rgba(Colormap::size * 4);
        for (int i = 0; i < Colormap::size; ++i) {
            for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = style.colormap->colours[i][c];
            rgba[i * 4 + 3] = 1.0f;
        }
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, Colormap::size, 1, 0, GL_RGBA, GL_FLOAT, rgba.data());
    }

    // Normalise on the CPU in double precision and upload as floats relative
    // to the colour range: float32 then loses nothing a 256-entry table can show.
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, p.field_texture);
    std::vector<float> texels(values.size());
    const double span = style.vmax - style.vmin;
    for (std::size_t i = 0; i < values.size(); ++i) texels[i] = static_cast<float>((values[i] - style.vmin) / span);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, cols, rows, 0, GL_RED, GL_FLOAT, texels.data());

    p.program.use();
    p.program.set("projection", canvas.projection());
    p.program.set("rect", glm::vec4(where.x, where.y, where.w, where.h));
    p.program.set("cells", glm::vec2(cols, rows));
    p.program.set("alpha", style.alpha);
    p.program.set("smooth_sampling", style.sampling == Sampling::smooth ? 1 : 0);
    p.program.set("field", 0);
    p.program.set("colormap", 1);
    glBindVertexArray(p.vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
    check_gl("draw_field");
}

}  // namespace render
