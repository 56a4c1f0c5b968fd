// The GL canvas's text (render/text.hpp): each font's faces get a
// single-channel atlas of their glyphs' coverage bitmaps, shelf-packed,
// kept in memory and uploaded when a batch is drawn; a line's glyphs are
// quads textured from it, one draw call per font and face.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "render/gl/gl_backend.hpp"
#include "render/gl/gl_context.hpp"
#include "render/gl/program.hpp"
#include "render/text.hpp"

namespace render {
namespace {

// Zero texels around every bitmap in the atlas. Quads reach one texel past
// their bitmap so that linear filtering can fade the edge out, and a pixel
// centre may lie half a pixel outside the quad under multisampling: two
// texels keep every sample off the neighbouring glyphs.
constexpr int pad = 2;
constexpr int atlas_min_width = 1024;
constexpr int atlas_start_height = 256;
// The tallest atlas a face may fill in memory: 1024 x 8192 bytes, some 3,000
// CJK glyphs at 40 px (bind_atlas also checks GL's own limit).
constexpr int max_atlas_height = 8192;

const char* const vertex_shader = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 texel;
layout(location = 2) in vec4 colour;
uniform mat4 projection;
out vec2 v_texel;
out vec4 v_colour;
void main() {
    v_texel = texel;
    v_colour = colour;
    gl_Position = projection * vec4(position, 0.0, 1.0);
})";

// The atlas holds coverage, which scales the colour's alpha.
const char* const fragment_shader = R"(#version 330 core
uniform sampler2D atlas;
in vec2 v_texel;
in vec4 v_colour;
out vec4 out_colour;
void main() {
    float coverage = texture(atlas, v_texel / vec2(textureSize(atlas, 0))).r;
    out_colour = vec4(v_colour.rgb, v_colour.a * coverage);
})";

// Shared by every batch of this kind, created on first use.
StreamPipeline& pipeline() {
    static StreamPipeline p{vertex_shader, fragment_shader};
    return p;
}

// A glyph's place in its face's atlas.
struct Glyph {
    float left = 0, top = 0;       // bitmap's top-left corner relative to the pen, y up (FreeType's bitmap_left/top)
    int width = 0, height = 0;     // bitmap size, pixels
    int atlas_x = 0, atlas_y = 0;  // bitmap's top-left texel in the atlas
};

// Shelf-packed R8 coverage atlas with a copy in memory: it grows by
// doubling its height and is uploaded lazily, when a batch is drawn.
struct FaceAtlas {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;
    int shelf_x = 0, shelf_y = 0, shelf_height = 0;
    int dirty_top = 0, dirty_bottom = 0;  // rows changed since the last upload
    GLuint texture = 0;
    int texture_height = 0;  // rows allocated on the GL side
    std::unordered_map<unsigned, Glyph> glyphs;  // by glyph index
};

// A font's atlases, one per face, kept in the font's backend cache.
struct FontAtlases {
    std::vector<std::unique_ptr<FaceAtlas>> faces;
    ~FontAtlases() {
        for (const auto& f : faces)
            if (f && f->texture) glDeleteTextures(1, &f->texture);
    }
};

FaceAtlas& face_atlas(const Font& font, std::uint32_t face) {
    std::shared_ptr<void>& cache = font.backend_cache();
    if (!cache) cache = std::make_shared<FontAtlases>();
    auto& faces = static_cast<FontAtlases*>(cache.get())->faces;
    if (faces.size() <= face) faces.resize(face + 1);
    if (!faces[face]) {
        auto a = std::make_unique<FaceAtlas>();
        // Wide enough for the face's widest possible glyph.
        a->width = std::max(atlas_min_width, static_cast<int>(std::ceil(font.widest(face))) + 2 * pad + 2);
        a->height = atlas_start_height;
        a->pixels.assign(static_cast<std::size_t>(a->width) * a->height, 0);
        a->shelf_x = a->shelf_y = pad;
        faces[face] = std::move(a);
    }
    return *faces[face];
}

// Copies a bitmap into the atlas.
void place(FaceAtlas& a, const std::string& path, Glyph& g, const unsigned char* rows, int pitch) {
    if (g.width + 2 * pad > a.width)
        throw std::runtime_error("glyph of " + std::to_string(g.width) + " px is wider than the font atlas");
    if (a.shelf_x + g.width + pad > a.width) {  // start the next shelf
        a.shelf_y += a.shelf_height;
        a.shelf_x = pad;
        a.shelf_height = 0;
    }
    while (a.shelf_y + g.height + pad > a.height) {
        if (2 * a.height > max_atlas_height)
            throw std::runtime_error("font atlas for " + path + " is full (" + std::to_string(a.width) + "x" +
                                     std::to_string(a.height) + ")");
        a.height *= 2;
        a.pixels.resize(static_cast<std::size_t>(a.width) * a.height, 0);
    }
    g.atlas_x = a.shelf_x;
    g.atlas_y = a.shelf_y;
    // A negative pitch means FreeType stored the rows bottom-up.
    const unsigned char* first = pitch >= 0 ? rows : rows - static_cast<std::ptrdiff_t>(pitch) * (g.height - 1);
    for (int y = 0; y < g.height; ++y)
        std::memcpy(&a.pixels[static_cast<std::size_t>(g.atlas_y + y) * a.width + g.atlas_x],
                    first + static_cast<std::ptrdiff_t>(pitch) * y, static_cast<std::size_t>(g.width));
    const bool clean = a.dirty_bottom == a.dirty_top;
    a.dirty_top = clean ? g.atlas_y : std::min(a.dirty_top, g.atlas_y);
    a.dirty_bottom = clean ? g.atlas_y + g.height : std::max(a.dirty_bottom, g.atlas_y + g.height);
    a.shelf_x += g.width + pad;
    a.shelf_height = std::max(a.shelf_height, g.height + pad);
}

// A glyph of the atlas, rasterised and placed on first use.
const Glyph& glyph(const Font& font, FaceAtlas& atlas, std::uint32_t face, unsigned index) {
    if (const auto found = atlas.glyphs.find(index); found != atlas.glyphs.end()) return found->second;
    const Font::Bitmap bitmap = font.rasterise(face, index);
    Glyph g;
    g.left = bitmap.left;
    g.top = bitmap.top;
    g.width = bitmap.width;
    g.height = bitmap.height;
    if (g.width > 0 && g.height > 0) place(atlas, font.face_file(face).path, g, bitmap.rows, bitmap.pitch);
    return atlas.glyphs.emplace(index, g).first->second;
}

// Uploads the glyphs placed since the last draw and binds the atlas to
// texture unit 0.
void bind(FaceAtlas& a, const std::string& path) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (a.height > max_size)
        throw std::runtime_error("font atlas for " + path + " (" + std::to_string(a.width) + "x" +
                                 std::to_string(a.height) + ") is larger than GL's textures");
    glActiveTexture(GL_TEXTURE0);
    if (!a.texture) {
        glGenTextures(1, &a.texture);
        glBindTexture(GL_TEXTURE_2D, a.texture);
        // Linear: quads sit at fractional pen positions, between texels.
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glBindTexture(GL_TEXTURE_2D, a.texture);
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of single bytes
    if (a.texture_height != a.height) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, a.width, a.height, 0, GL_RED, GL_UNSIGNED_BYTE, a.pixels.data());
        a.texture_height = a.height;
    } else if (a.dirty_bottom > a.dirty_top) {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, a.dirty_top, a.width, a.dirty_bottom - a.dirty_top, GL_RED,
                        GL_UNSIGNED_BYTE, &a.pixels[static_cast<std::size_t>(a.dirty_top) * a.width]);
    }
    a.dirty_top = a.dirty_bottom = 0;
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    check_gl("the glyph atlas");
}

struct Vertex {
    glm::vec2 position;  // pixels
    glm::vec2 texel;     // atlas texels, normalised in the shader since the atlas may grow
    glm::vec4 colour;    // straight alpha
};
struct Batch {
    const Font* font;
    std::uint32_t face;
    FaceAtlas* atlas;
    std::vector<Vertex> vertices;
};

// The quads of every line, one batch per font and face in the order they
// first appear.
std::vector<Batch> batches_of(const Text& text) {
    std::vector<Batch> batches;
    for (const Text::Line& line : text.lines()) {
        const Font& font = *line.font;
        const Rotation rotate(line.rotation_degrees);
        const glm::vec2 origin = line.origin;
        const glm::vec4 colour = line.colour;
        for (const Font::ShapedGlyph& placed : line.shaped.glyphs) {
            FaceAtlas& atlas = face_atlas(font, placed.face);
            const Glyph& g = glyph(font, atlas, placed.face, placed.index);
            if (g.width <= 0 || g.height <= 0) continue;
            auto batch = std::find_if(batches.begin(), batches.end(),
                                      [&](const Batch& b) { return b.font == &font && b.face == placed.face; });
            if (batch == batches.end()) batch = batches.insert(batches.end(), Batch{&font, placed.face, &atlas, {}});
            // One texel of the zero border on each side, so the edge fades out under filtering.
            const glm::vec2 q0 = placed.position + glm::vec2(g.left - 1, -g.top - 1);
            const glm::vec2 size{static_cast<float>(g.width + 2), static_cast<float>(g.height + 2)};
            const glm::vec2 t0{static_cast<float>(g.atlas_x - 1), static_cast<float>(g.atlas_y - 1)};
            const Vertex tl{origin + rotate(q0), t0, colour};
            const Vertex tr{origin + rotate(q0 + glm::vec2(size.x, 0)), t0 + glm::vec2(size.x, 0), colour};
            const Vertex bl{origin + rotate(q0 + glm::vec2(0, size.y)), t0 + glm::vec2(0, size.y), colour};
            const Vertex br{origin + rotate(q0 + size), t0 + size, colour};
            batch->vertices.insert(batch->vertices.end(), {tl, tr, br, tl, br, bl});
        }
    }
    return batches;
}

}  // namespace

void gl_backend::text(const Canvas& canvas, const Text& text) {
    StreamPipeline& p = pipeline();
    canvas.bind();
    p.program.use();
    p.program.set("projection", canvas.projection());
    p.program.set("atlas", 0);
    glBindVertexArray(p.vao);
    glBindBuffer(GL_ARRAY_BUFFER, p.vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, texel)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, colour)));
    for (Batch& batch : batches_of(text)) {
        if (batch.vertices.empty()) continue;
        bind(*batch.atlas, batch.font->face_file(batch.face).path);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(batch.vertices.size() * sizeof(Vertex)),
                     batch.vertices.data(), GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(batch.vertices.size()));
    }
    glBindVertexArray(0);
    check_gl("Text::draw");
}

}  // namespace render
