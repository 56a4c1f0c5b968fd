#pragma once
// Text: a FreeType face at one pixel size whose glyphs are rasterised on
// demand into a single-channel atlas texture, and a batch of strings drawn
// from it. Single lines only; pixel coordinates, origin top left, y down.

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "render/canvas.hpp"
#include "render/gl.hpp"
#include "render/gl_backend.hpp"

// FreeType's handle types, declared here so that its headers stay in text.cpp.
struct FT_LibraryRec_;
struct FT_FaceRec_;

namespace render {

enum class Align { left, centre, right };                // horizontal anchor of the given point
enum class Baseline { top, middle, baseline, bottom };  // vertical anchor: top of the line box, middle of the
                                                        // capitals, the baseline, bottom of the line box

class Font {
public:
    // Throws std::runtime_error naming `path` if the face cannot be loaded,
    // std::invalid_argument if pixel_size is not positive.
    explicit Font(float pixel_size, const std::string& path = FIGGEN_FONT_PATH);
    ~Font();
    Font(const Font&) = delete;
    Font& operator=(const Font&) = delete;

    float pixel_size() const { return pixel_size_; }  // the em size, pixels
    float ascender() const { return ascender_; }      // baseline to top of the line box, positive
    float descender() const { return descender_; }    // baseline to bottom of the line box, negative (FreeType's sign)
    float line_height() const { return line_height_; }  // baseline to baseline
    float cap_height() const { return cap_height_; }    // baseline to the top of "H"
    const std::string& path() const { return path_; }

    // Advance width of a line, pixels, kerning included (not the ink's extent).
    float width(std::string_view utf8) const;

private:
    friend class Text;
    friend void gl_backend::text(const Canvas& canvas, const Text& text);

    struct Glyph {
        unsigned index = 0;      // FreeType glyph index: 0 is the font's .notdef box
        float advance = 0;       // unhinted, pixels
        int left = 0, top = 0;   // bitmap's top-left corner relative to the pen, y up (FreeType's bitmap_left/top)
        int width = 0, height = 0;      // bitmap size, pixels
        int atlas_x = 0, atlas_y = 0;   // bitmap's top-left texel in the atlas
    };

    // Shelf-packed R8 coverage atlas with a copy in memory: it grows by
    // doubling its height and is uploaded lazily, when a batch is drawn.
    struct Atlas {
        int width = 0, height = 0;
        std::vector<std::uint8_t> pixels;
        int shelf_x = 0, shelf_y = 0, shelf_height = 0;
        int dirty_top = 0, dirty_bottom = 0;  // rows changed since the last upload
        GLuint texture = 0;
        int texture_height = 0;               // rows allocated on the GL side
    };

    const Glyph& glyph(char32_t codepoint) const;  // from the cache, rasterised on first use
    float kerning(const Glyph& left, const Glyph& right) const;
    float width(const std::u32string& codepoints) const;
    void place(Glyph& glyph, const unsigned char* rows, int pitch) const;  // copies a bitmap into the atlas
    void bind_atlas() const;  // uploads new glyphs, binds the atlas to texture unit 0

    float pixel_size_;
    std::string path_;
    FT_LibraryRec_* library_ = nullptr;
    FT_FaceRec_* face_ = nullptr;
    float scale_ = 0;  // pixels per font unit
    float ascender_ = 0, descender_ = 0, line_height_ = 0, cap_height_ = 0;
    bool has_kerning_ = false;
    mutable std::unordered_map<char32_t, Glyph> glyphs_;  // a cache: filling it does not change what the font is
    mutable Atlas atlas_;
};

// A batch of strings, drawn with one draw call per font. The fonts must
// outlive the batch's last draw().
class Text {
public:
    // `position` is the anchor named by align and baseline; the line turns
    // `rotation_degrees` counter-clockwise on screen about it (90 for a
    // y-axis label, reading bottom to top).
    void add(Font& font, std::string_view utf8, glm::vec2 position, const glm::vec4& colour,
             Align align = Align::left, Baseline baseline = Baseline::baseline, float rotation_degrees = 0);

    bool empty() const { return lines_.empty(); }
    void clear() {
        batches_.clear();
        lines_.clear();
    }
    // Draws every line on `surface` (render/surface.hpp).
    void draw(Surface& surface) const;

    // Each line as laid out, for backends that draw glyphs from the font
    // itself (the vector page): the same glyphs at the same pen positions
    // as the GL quads.
    struct PlacedGlyph {
        unsigned index;  // FreeType glyph index in the font's face
        float pen;       // along the baseline from the origin, pixels
    };
    struct Line {
        const Font* font;
        glm::vec2 origin;        // the pen's start on the baseline, pixels
        float rotation_degrees;  // counter-clockwise on screen about the origin
        glm::vec4 colour;
        std::vector<PlacedGlyph> glyphs;  // one a character of `utf8`
        std::string utf8;
    };
    const std::vector<Line>& lines() const { return lines_; }

private:
    friend void gl_backend::text(const Canvas& canvas, const Text& text);

    struct Vertex {
        glm::vec2 position;  // pixels
        glm::vec2 texel;     // atlas texels, normalised in the shader since the atlas may grow
        glm::vec4 colour;    // straight alpha
    };
    struct Batch {
        const Font* font;
        std::vector<Vertex> vertices;
    };
    std::vector<Batch> batches_;
    std::vector<Line> lines_;
};

// DejaVu Sans at `pixels`, made once per size and kept for the process: a
// font's glyph atlas is costly to fill, and every figure draws titles.
Font& font_of_size(float pixels);
// Forgets every cached font. Called before each figure, so that a figure's
// glyph atlases, and with them its exact pixels, never depend on what was
// drawn before it in the same process.
void clear_font_cache();

}  // namespace render
