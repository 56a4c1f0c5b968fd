// The GL canvas's fields (render/field.hpp): the values as a float
// texture, coloured through the colormap's texture in the shader, smooth
// by a cubic B-spline (on the CPU for a film's pair on llvmpipe).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "render/field.hpp"
#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/program.hpp"

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

// The fragment shader, compiled once per sampling and layer count (the
// #defines SMOOTH and LAYERS come first): llvmpipe runs both sides of a
// branch, so a nearest field would pay for the spline and one layer for two.
const char* const fragment_body = R"(
in vec2 field_position;
out vec4 out_colour;
uniform sampler2D field;     // R32F (one layer) or RG32F (two), texel (col, row): (value - vmin) / (vmax - vmin)
uniform sampler2D colormap;  // N x layers RGBA32F, a row per layer
uniform vec2 alpha;          // per layer

vec2 cell(ivec2 p) {
    ivec2 size = textureSize(field, 0);
    return texelFetch(field, clamp(p, ivec2(0), size - 1), 0).rg;  // edge cells repeat, as Agg clamps
}

// Cubic B-spline weights for fractional offset t (Agg's image_filter_bicubic).
vec4 bspline(vec2 t, int axis) {
    float u = t[axis], s = 1.0 - u;
    return vec4(s * s * s, 4.0 - 6.0 * u * u + 3.0 * u * u * u, 4.0 - 6.0 * s * s + 3.0 * s * s * s, u * u * u) / 6.0;
}

// Both layers' values at once: a texel fetch filters every channel alike,
// so each layer gets the value it would get alone.
vec2 sample_field() {
#if SMOOTH == 0
    return cell(ivec2(floor(field_position)));
#else
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
    return g0.y * (g0.x * texture(field, vec2(h0.x, h0.y) / size).rg + g1.x * texture(field, vec2(h1.x, h0.y) / size).rg) +
           g1.y * (g0.x * texture(field, vec2(h0.x, h1.y) / size).rg + g1.x * texture(field, vec2(h1.x, h1.y) / size).rg);
#endif
}

void main() {
    vec2 t = sample_field();
    // matplotlib's lookup: index floor(t * N) clipped to 0..N-1.
    int n = textureSize(colormap, 0).x;
    ivec2 index = clamp(ivec2(floor(t * float(n))), ivec2(0), ivec2(n - 1));
    vec3 first = texelFetch(colormap, ivec2(index.x, 0), 0).rgb;
#if LAYERS == 1
    out_colour = vec4(first, alpha.x);
#else
    // The second layer over the first, premultiplied (blended with ONE,
    // ONE_MINUS_SRC_ALPHA): what two draws give, but for their rounding.
    vec3 second = texelFetch(colormap, ivec2(index.y, 1), 0).rgb;
    out_colour = vec4(second * alpha.y + first * (alpha.x * (1.0 - alpha.y)), alpha.y + alpha.x * (1.0 - alpha.y));
#endif
})";

std::string fragment_shader(bool smooth, int layers) {
    return std::string("#version 330 core\n#define SMOOTH ") + (smooth ? "1" : "0") + "\n#define LAYERS " +
           std::to_string(layers) + "\n" + fragment_body;
}

struct Pipeline {
    std::unique_ptr<Program> programs[2][2];  // [smooth][layers - 1], compiled on first use
    GLuint vao = 0, field_texture = 0, colormap_texture = 0;
    // What the textures hold, so that a film's frames, which draw the same
    // colour table into a field of the same size frame after frame, send
    // only what changed: the table when its colours differ, and the cells
    // into the texture already there (no reallocation, no page faults).
    std::vector<glm::vec4> colormap_loaded;
    int field_rows = 0, field_cols = 0, field_layers = 0;
    std::vector<float> texels;     // the normalised cells, kept between draws
    std::vector<float> across;     // resample_smooth's pass along the rows
    std::vector<float> resampled;  // and its result, a value per pixel
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

const Program& program(Pipeline& p, bool smooth, int layers) {
    std::unique_ptr<Program>& variant = p.programs[smooth ? 1 : 0][layers - 1];
    if (!variant) variant = std::make_unique<Program>(vertex_shader, fragment_shader(smooth, layers).c_str());
    return *variant;
}

// The colour tables as N x layers RGBA texels, a row per layer, sent only
// when they differ from those loaded (compared by colours: a map's address
// may be reused by another).
void load_colormaps(Pipeline& p, std::span<const FieldStyle* const> styles) {
    const int n = styles[0]->colormap->size();
    std::vector<glm::vec4> rgba;
    rgba.reserve(static_cast<std::size_t>(n) * styles.size());
    for (const FieldStyle* style : styles)
        for (int i = 0; i < n; ++i) rgba.push_back(glm::vec4(style->colormap->colours[i], 1.0f));
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, p.colormap_texture);
    if (rgba == p.colormap_loaded) return;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, static_cast<int>(styles.size()), 0, GL_RGBA, GL_FLOAT, rgba.data());
    p.colormap_loaded = std::move(rgba);
}

// Normalise on the CPU in double precision to floats relative to the colour
// range: float32 then loses nothing a lookup table can show. Layers
// interleave, one channel each.
void normalise(Pipeline& p, std::span<const std::span<const double>> values, std::span<const FieldStyle* const> styles) {
    const std::size_t layers = values.size(), cells = values[0].size();
    p.texels.resize(cells * layers);
    for (std::size_t l = 0; l < layers; ++l) {
        const double vmin = styles[l]->vmin, span = styles[l]->vmax - styles[l]->vmin;
        for (std::size_t i = 0; i < cells; ++i)
            p.texels[i * layers + l] = static_cast<float>((values[l][i] - vmin) / span);
    }
}

// Sends rows x cols texels of `layers` channels into the field texture.
void upload(Pipeline& p, int rows, int cols, int layers, const float* texels) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, p.field_texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const GLenum format = layers == 1 ? GL_RED : GL_RG;
    if (rows == p.field_rows && cols == p.field_cols && layers == p.field_layers) {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, cols, rows, format, GL_FLOAT, texels);
    } else {
        glTexImage2D(GL_TEXTURE_2D, 0, layers == 1 ? GL_R32F : GL_RG32F, cols, rows, 0, format, GL_FLOAT, texels);
        p.field_rows = rows;
        p.field_cols = cols;
        p.field_layers = layers;
    }
}

void resample_smooth(Pipeline& p, int rows, int cols, int layers, int width, int height) {
    spline_resample(p.texels, rows, cols, layers, width, height, p.across, p.resampled);
}

// Buffers larger than this are released after each draw rather than kept
// for the next frame (a 4K film's would hold 130 MB for the process's life).
constexpr std::size_t max_kept_floats = 4u << 20;  // 16 MiB

void release_if_large(std::vector<float>& buffer) {
    if (buffer.capacity() > max_kept_floats) std::vector<float>().swap(buffer);
}

// Whether the CPU resamples a smooth pair (set_field_resampling).
bool resample_on_cpu() {
    switch (field_resampling()) {
    case FieldResampling::cpu:
        return true;
    case FieldResampling::sampler:
        return false;
    case FieldResampling::automatic:
        break;
    }
    return is_llvmpipe(GlContext::get().renderer());
}

bool whole(const Rect& r) {
    return r.x == std::floor(r.x) && r.y == std::floor(r.y) && r.w == std::floor(r.w) && r.h == std::floor(r.h);
}

}  // namespace

void gl_backend::field(const Canvas& canvas, const Rect& where, int rows, int cols,
                       std::span<const std::span<const double>> values, std::span<const FieldStyle* const> styles) {
    Pipeline& p = pipeline();
    canvas.bind();

    load_colormaps(p, styles);
    normalise(p, values, styles);
    const int layers = static_cast<int>(values.size());
    bool smooth = styles[0]->sampling == Sampling::smooth;
    glm::vec2 cells(cols, rows);
    // A smooth pair (a film's frame) on whole pixels, on llvmpipe: the
    // spline on the CPU, one value a pixel, drawn as nearest cells of one
    // pixel each. A GPU's sampler does it faster in the shader.
    if (smooth && layers == 2 && whole(where) && where.w >= 1 && where.h >= 1 && resample_on_cpu()) {
        const int width = static_cast<int>(where.w), height = static_cast<int>(where.h);
        resample_smooth(p, rows, cols, layers, width, height);
        upload(p, height, width, layers, p.resampled.data());
        cells = glm::vec2(width, height);
        smooth = false;
    } else {
        upload(p, rows, cols, layers, p.texels.data());
    }
    for (auto* buffer : {&p.texels, &p.across, &p.resampled}) release_if_large(*buffer);

    const Program& prog = program(p, smooth, layers);
    prog.use();
    prog.set("projection", canvas.projection());
    prog.set("rect", glm::vec4(where.x, where.y, where.w, where.h));
    prog.set("cells", cells);
    prog.set("alpha", glm::vec2(styles[0]->alpha, layers == 2 ? styles[1]->alpha : 0.0f));
    prog.set("field", 0);
    prog.set("colormap", 1);
    glBindVertexArray(p.vao);
    // A field fills an axis-aligned rectangle: its edges need no coverage
    // samples, and without them llvmpipe shades each pixel once, not once
    // per sample.
    glDisable(GL_MULTISAMPLE);
    if (layers == 2) glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    canvas.bind();  // the canvas's own blending and multisampling again
    glBindVertexArray(0);
    check_gl(values.size() == 2 ? "draw_field_pair" : "draw_field");
}

}  // namespace render
