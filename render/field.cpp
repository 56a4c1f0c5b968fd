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
uniform sampler2D colormap;  // N x 1 RGBA32F
uniform float alpha;
uniform int smooth_sampling;

float cell(ivec2 p) {
    ivec2 size = textureSize(field, 0);
    return texelFetch(field, clamp(p, ivec2(0), size - 1), 0).r;  // edge cells repeat, as Agg clamps
}

// Cubic B-spline weights for fractional offset t (Agg's image_filter_bicubic).
vec4 bspline(vec2 t, int axis) {
    float u = t[axis], s = 1.0 - u;
    return vec4(s * s * s, 4.0 - 6.0 * u * u + 3.0 * u * u * u, 4.0 - 6.0 * s * s + 3.0 * s * s * s, u * u * u) / 6.0;
}

float sample_field() {
    if (smooth_sampling == 0) return cell(ivec2(floor(field_position)));
    // The 4 x 4 B-spline as 4 bilinear fetches (Sigg & Hadwiger, GPU Gems 2,
    // ch. 20): the weights are all positive, so each pair of taps is one
    // linear fetch at the point between them that splits the pair's weight.
    // llvmpipe runs shaders on the CPU: 4 fetches instead of 16 is most of
    // the cost of a smooth frame.
    vec2 p = field_position - 0.5;  // cell centres sit at half-integers
    vec2 base = floor(p);
    vec2 t = p - base;
    vec4 wx = bspline(t, 0), wy = bspline(t, 1);
    vec2 g0 = vec2(wx.x + wx.y, wy.x + wy.y), g1 = vec2(wx.z + wx.w, wy.z + wy.w);
    vec2 h0 = base - 0.5 + vec2(wx.y, wy.y) / g0;  // texel-space points, texel i centred at i + 0.5
    vec2 h1 = base + 1.5 + vec2(wx.w, wy.w) / g1;
    vec2 size = vec2(textureSize(field, 0));
    return g0.y * (g0.x * texture(field, vec2(h0.x, h0.y) / size).r + g1.x * texture(field, vec2(h1.x, h0.y) / size).r) +
           g1.y * (g0.x * texture(field, vec2(h0.x, h1.y) / size).r + g1.x * texture(field, vec2(h1.x, h1.y) / size).r);
}

void main() {
    float t = sample_field();
    // matplotlib's lookup: index floor(t * N) clipped to 0..N-1.
    int n = textureSize(colormap, 0).x;
    int index = clamp(int(floor(t * float(n))), 0, n - 1);
    out_colour = vec4(texelFetch(colormap, ivec2(index, 0), 0).rgb, alpha);
})";

struct Pipeline {
    Program program{vertex_shader, fragment_shader};
    GLuint vao = 0, field_texture = 0, colormap_texture = 0;
    // What the textures hold, so that a film's frames, which draw the same
    // colour table into a field of the same size frame after frame, send
    // only what changed: the table when its colours differ, and the cells
    // into the texture already there (no reallocation, no page faults).
    std::vector<glm::vec4> colormap_loaded;
    int field_rows = 0, field_cols = 0;
    std::vector<float> texels;  // the upload buffer, kept between draws
    Pipeline() {
        glGenVertexArrays(1, &vao);
        glGenTextures(1, &field_texture);
        glGenTextures(1, &colormap_texture);
        for (GLuint texture : {field_texture, colormap_texture}) {
            // The field filters linearly for the smooth path's fetches (texelFetch ignores it).
            const GLint filter = texture == field_texture ? GL_LINEAR : GL_NEAREST;
            glBindTexture(GL_TEXTURE_2D, texture);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
    }
};

Pipeline& pipeline() {
    static Pipeline p;
    return p;
}

// The colour table as N x 1 RGBA texels, sent only when it differs from the
// one loaded (compared by colours: a map's address may be reused by another).
void load_colormap(Pipeline& p, const Colormap& map) {
    const int n = map.size();
    std::vector<glm::vec4> rgba(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) rgba[i] = glm::vec4(map.colours[i], 1.0f);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, p.colormap_texture);
    if (rgba == p.colormap_loaded) return;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, 1, 0, GL_RGBA, GL_FLOAT, rgba.data());
    p.colormap_loaded = std::move(rgba);
}

// Normalise on the CPU in double precision and upload as floats relative
// to the colour range: float32 then loses nothing a lookup table can show.
void load_field(Pipeline& p, int rows, int cols, std::span<const double> values, const FieldStyle& style) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, p.field_texture);
    p.texels.resize(values.size());
    const double span = style.vmax - style.vmin;
    for (std::size_t i = 0; i < values.size(); ++i) p.texels[i] = static_cast<float>((values[i] - style.vmin) / span);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (rows == p.field_rows && cols == p.field_cols) {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, cols, rows, GL_RED, GL_FLOAT, p.texels.data());
    } else {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, cols, rows, 0, GL_RED, GL_FLOAT, p.texels.data());
        p.field_rows = rows;
        p.field_cols = cols;
    }
}

}  // namespace

void draw_field(const Canvas& canvas, const Rect& where, int rows, int cols, std::span<const double> values,
                const FieldStyle& style) {
    if (rows < 1 || cols < 1 || values.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols))
        throw std::invalid_argument("draw_field: " + std::to_string(values.size()) + " values do not fill " +
                                    std::to_string(rows) + "x" + std::to_string(cols) + " cells");
    if (!style.colormap) throw std::invalid_argument("draw_field: no colormap");
    if (!(style.vmax > style.vmin)) throw std::invalid_argument("draw_field: vmax must exceed vmin");
    Pipeline& p = pipeline();
    canvas.bind();

    load_colormap(p, *style.colormap);
    load_field(p, rows, cols, values, style);

    p.program.use();
    p.program.set("projection", canvas.projection());
    p.program.set("rect", glm::vec4(where.x, where.y, where.w, where.h));
    p.program.set("cells", glm::vec2(cols, rows));
    p.program.set("alpha", style.alpha);
    p.program.set("smooth_sampling", style.sampling == Sampling::smooth ? 1 : 0);
    p.program.set("field", 0);
    p.program.set("colormap", 1);
    glBindVertexArray(p.vao);
    // A field fills an axis-aligned rectangle: its edges need no coverage
    // samples, and without them llvmpipe shades each pixel once, not once
    // per sample.
    glDisable(GL_MULTISAMPLE);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glEnable(GL_MULTISAMPLE);
    glBindVertexArray(0);
    check_gl("draw_field");
}

}  // namespace render
