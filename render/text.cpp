#include "render/text.hpp"

#include <map>
#include <memory>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_TRUETYPE_TABLES_H

#include "render/gl_context.hpp"
#include "render/program.hpp"
#include "render/utf8.hpp"

namespace render {
namespace {

// Zero texels around every bitmap in the atlas. Quads reach one texel past
// their bitmap so that linear filtering can fade the edge out, and a pixel
// centre may lie half a pixel outside the quad under multisampling: two
// texels keep every sample off the neighbouring glyphs.
constexpr int pad = 2;
constexpr int atlas_min_width = 1024;
constexpr int atlas_start_height = 256;

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

std::string freetype_error(FT_Error error) {
    const char* text = FT_Error_String(error);  // null unless FreeType was built with error strings
    return text ? text : "FreeType error " + std::to_string(error);
}

// Rotation by `degrees` counter-clockwise on screen, in y-down coordinates.
// Quarter turns are exact so that rotated labels still meet the pixel grid.
struct Rotation {
    float c = 1, s = 0;
    explicit Rotation(float degrees) {
        const float turns = degrees / 90.0f;
        if (turns == std::floor(turns)) {
            static constexpr float cosines[] = {1, 0, -1, 0}, sines[] = {0, 1, 0, -1};
            const int quarter = static_cast<int>(std::fmod(std::fmod(turns, 4.0f) + 4.0f, 4.0f));
            c = cosines[quarter], s = sines[quarter];
        } else {
            const float radians = degrees * 3.14159265358979f / 180.0f;
            c = std::cos(radians), s = std::sin(radians);
        }
    }
    glm::vec2 operator()(glm::vec2 v) const { return {c * v.x + s * v.y, -s * v.x + c * v.y}; }
};

}  // namespace

Font::Font(float pixel_size, const std::string& path) : pixel_size_(pixel_size), path_(path) {
    if (!(pixel_size > 0)) throw std::invalid_argument("font pixel size must be positive, got " + std::to_string(pixel_size));
    GlContext::get();
    if (const FT_Error error = FT_Init_FreeType(&library_))
        throw std::runtime_error("cannot start FreeType for font " + path + ": " + freetype_error(error));
    if (const FT_Error error = FT_New_Face(library_, path.c_str(), 0, &face_)) {
        FT_Done_FreeType(library_);
        throw std::runtime_error("cannot load font " + path + ": " + freetype_error(error));
    }
    // Fractional sizes are fine: 26.6 fixed point at 72 dpi is pixels.
    const auto size_26_6 = static_cast<FT_F26Dot6>(std::lround(pixel_size * 64));
    if (!FT_IS_SCALABLE(face_) || FT_Set_Char_Size(face_, 0, size_26_6, 72, 72) != 0) {
        FT_Done_Face(face_);
        FT_Done_FreeType(library_);
        throw std::runtime_error("font " + path + " cannot be scaled to " + std::to_string(pixel_size) + " px");
    }
    // Metrics from font units rather than face->size->metrics, which FreeType
    // rounds to whole pixels.
    scale_ = static_cast<float>(size_26_6) / 64.0f / static_cast<float>(face_->units_per_EM);
    ascender_ = static_cast<float>(face_->ascender) * scale_;
    descender_ = static_cast<float>(face_->descender) * scale_;
    line_height_ = static_cast<float>(face_->height) * scale_;
    const auto* os2 = static_cast<const TT_OS2*>(FT_Get_Sfnt_Table(face_, FT_SFNT_OS2));
    if (os2 && os2->version >= 2 && os2->sCapHeight > 0) {
        cap_height_ = static_cast<float>(os2->sCapHeight) * scale_;
    } else if (FT_Load_Char(face_, 'H', FT_LOAD_NO_SCALE) == 0) {  // older tables: measure the letter itself
        cap_height_ = static_cast<float>(face_->glyph->metrics.horiBearingY) * scale_;
    } else {
        cap_height_ = 0.7f * pixel_size;
    }
    has_kerning_ = FT_HAS_KERNING(face_);

    // Wide enough for the font's widest possible glyph.
    const float widest = static_cast<float>(face_->bbox.xMax - face_->bbox.xMin) * scale_;
    atlas_.width = std::max(atlas_min_width, static_cast<int>(std::ceil(widest)) + 2 * pad + 2);
    atlas_.height = atlas_start_height;
    atlas_.pixels.assign(static_cast<std::size_t>(atlas_.width) * atlas_.height, 0);
    atlas_.shelf_x = atlas_.shelf_y = pad;
}

Font::~Font() {
    if (atlas_.texture) glDeleteTextures(1, &atlas_.texture);
    FT_Done_Face(face_);
    FT_Done_FreeType(library_);
}

float Font::width(std::string_view utf8) const { return width(decode_utf8(utf8)); }

float Font::width(const std::u32string& codepoints) const {
    float pen = 0;
    const Glyph* previous = nullptr;
    for (const char32_t c : codepoints) {
        const Glyph& g = glyph(c);
        if (previous) pen += kerning(*previous, g);
        pen += g.advance;
        previous = &g;
    }
    return pen;
}

float Font::kerning(const Glyph& left, const Glyph& right) const {
    if (!has_kerning_) return 0;
    FT_Vector delta{};
    // Unscaled, then scaled here: FreeType's scaled kerning is rounded to 1/64 px or whole pixels.
    if (FT_Get_Kerning(face_, left.index, right.index, FT_KERNING_UNSCALED, &delta) != 0) return 0;
    return static_cast<float>(delta.x) * scale_;
}

const Font::Glyph& Font::glyph(char32_t codepoint) const {
    if (const auto found = glyphs_.find(codepoint); found != glyphs_.end()) return found->second;
    Glyph g;
    g.index = FT_Get_Char_Index(face_, codepoint);  // 0, the .notdef box, when the font lacks it
    // Light hinting snaps only vertically (baseline, x-height), which keeps
    // the unhinted advances below true; the bitmap is 8-bit grey coverage.
    if (const FT_Error error = FT_Load_Glyph(face_, g.index, FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT)) {
        char name[16];
        std::snprintf(name, sizeof name, "U+%04lX", static_cast<unsigned long>(codepoint));
        throw std::runtime_error(std::string("cannot render glyph ") + name + " of " + path_ + ": " +
                                 freetype_error(error));
    }
    const FT_GlyphSlot slot = face_->glyph;
    const FT_Bitmap& bitmap = slot->bitmap;
    if (bitmap.pixel_mode != FT_PIXEL_MODE_GRAY && bitmap.rows > 0)
        throw std::runtime_error("font " + path_ + " gave a glyph bitmap that is not 8-bit grey");
    g.advance = static_cast<float>(slot->linearHoriAdvance) / 65536.0f;  // 16.16 pixels, before hinting
    g.left = slot->bitmap_left;
    g.top = slot->bitmap_top;
    g.width = static_cast<int>(bitmap.width);
    g.height = static_cast<int>(bitmap.rows);
    if (g.width > 0 && g.height > 0) place(g, bitmap.buffer, bitmap.pitch);
    return glyphs_.emplace(codepoint, g).first->second;
}

void Font::place(Glyph& g, const unsigned char* rows, int pitch) const {
    Atlas& a = atlas_;
    if (g.width + 2 * pad > a.width)
        throw std::runtime_error("glyph of " + std::to_string(g.width) + " px is wider than the font atlas");
    if (a.shelf_x + g.width + pad > a.width) {  // start the next shelf
        a.shelf_y += a.shelf_height;
        a.shelf_x = pad;
        a.shelf_height = 0;
    }
    while (a.shelf_y + g.height + pad > a.height) {
        GLint max_size = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
        if (2 * a.height > max_size)
            throw std::runtime_error("font atlas for " + path_ + " is full (" + std::to_string(a.width) + "x" +
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

void Font::bind_atlas() const {
    Atlas& a = atlas_;
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
    check_gl("Font::bind_atlas");
}

void Text::add(Font& font, std::string_view utf8, glm::vec2 position, const glm::vec4& colour, Align align,
               Baseline baseline, float rotation_degrees) {
    const std::u32string codepoints = decode_utf8(utf8);
    if (codepoints.empty()) return;
    // The pen's start in the line's own frame (x along the baseline, y down), relative to the anchor.
    glm::vec2 start{0, 0};
    const float line_width = font.width(codepoints);
    if (align == Align::centre) start.x = -line_width / 2;
    if (align == Align::right) start.x = -line_width;
    switch (baseline) {
        case Baseline::top: start.y = font.ascender(); break;
        case Baseline::middle: start.y = font.cap_height() / 2; break;
        case Baseline::baseline: break;
        case Baseline::bottom: start.y = font.descender(); break;
    }
    const Rotation rotate(rotation_degrees);
    glm::vec2 origin = position + rotate(start);
    // Glyphs are hinted to whole pixels vertically: put the baseline on a
    // pixel edge too, or filtering blurs the crisp rows. Along the baseline
    // the pen keeps its fractional position, so spacing stays true.
    if (rotate.s == 0) origin.y = std::round(origin.y);
    if (rotate.c == 0) origin.x = std::round(origin.x);

    auto batch = std::find_if(batches_.begin(), batches_.end(), [&](const Batch& b) { return b.font == &font; });
    if (batch == batches_.end()) batch = batches_.insert(batches_.end(), Batch{&font, {}});
    std::vector<Vertex>& out = batch->vertices;
    Line& line = lines_.emplace_back(Line{&font, origin, rotation_degrees, colour, {}, std::string(utf8)});
    line.glyphs.reserve(codepoints.size());

    float pen = 0;
    const Font::Glyph* previous = nullptr;
    for (const char32_t c : codepoints) {
        const Font::Glyph& g = font.glyph(c);
        if (previous) pen += font.kerning(*previous, g);
        previous = &g;
        line.glyphs.push_back({g.index, pen});
        if (g.width > 0 && g.height > 0) {
            // One texel of the zero border on each side, so the edge fades out under filtering.
            const glm::vec2 q0{pen + static_cast<float>(g.left - 1), static_cast<float>(-g.top - 1)};
            const glm::vec2 size{static_cast<float>(g.width + 2), static_cast<float>(g.height + 2)};
            const glm::vec2 t0{static_cast<float>(g.atlas_x - 1), static_cast<float>(g.atlas_y - 1)};
            const Vertex tl{origin + rotate(q0), t0, colour};
            const Vertex tr{origin + rotate(q0 + glm::vec2(size.x, 0)), t0 + glm::vec2(size.x, 0), colour};
            const Vertex bl{origin + rotate(q0 + glm::vec2(0, size.y)), t0 + glm::vec2(0, size.y), colour};
            const Vertex br{origin + rotate(q0 + size), t0 + size, colour};
            out.insert(out.end(), {tl, tr, br, tl, br, bl});
        }
        pen += g.advance;
    }
}

void Text::draw(Surface& surface) const {
    if (!lines_.empty()) surface.text(*this);
}

void gl_backend::text(const Canvas& canvas, const Text& text) {
    StreamPipeline& p = pipeline();
    canvas.bind();
    p.program.use();
    p.program.set("projection", canvas.projection());
    p.program.set("atlas", 0);
    glBindVertexArray(p.vao);
    glBindBuffer(GL_ARRAY_BUFFER, p.vbo);
    glEnableVertexAttribArray(0);
    using Vertex = Text::Vertex;
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, texel)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, colour)));
    for (const Text::Batch& batch : text.batches_) {
        if (batch.vertices.empty()) continue;
        batch.font->bind_atlas();
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(batch.vertices.size() * sizeof(Vertex)),
                     batch.vertices.data(), GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(batch.vertices.size()));
    }
    glBindVertexArray(0);
    check_gl("Text::draw");
}

namespace {
std::map<float, std::unique_ptr<Font>>& font_cache() {
    static std::map<float, std::unique_ptr<Font>> fonts;
    return fonts;
}
}  // namespace

void clear_font_cache() { font_cache().clear(); }

Font& font_of_size(float pixels) {
    auto& font = font_cache()[pixels];
    if (!font) font = std::make_unique<Font>(pixels);
    return *font;
}

}  // namespace render
