#pragma once
// Text: lines shaped by HarfBuzz through libraqm (kerning, ligatures,
// combining marks, right-to-left and mixed directions by FriBidi), from the
// figure's font (DejaVu Sans) and, for characters it lacks, from the
// fallback faces fontconfig finds (render/font_fallback.hpp). A batch of
// strings (Text) is drawn by a backend: the GL canvas from a glyph atlas
// (render/gl/text_gl.cpp), the vector page from the glyphs' outlines.
// Single lines; wrap() breaks a
// paragraph into lines by the Unicode line-breaking rules (libunibreak).
// Pixel coordinates, origin top left, y down.

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "render/font_fallback.hpp"
#include "render/surface.hpp"

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

    // Advance width of a line as shaped, pixels (not the ink's extent).
    // `language` (e.g. "zh-cn", "ja"; empty: none) picks the fallback faces
    // and the language's glyph forms.
    float width(std::string_view utf8, std::string_view language = {}) const;

    // A line laid out: its glyphs in visual order (left to right on the
    // page), each from face `face` of this font (0 is the font's own file).
    struct ShapedGlyph {
        std::uint32_t face;
        unsigned index;      // glyph index in that face: 0 is its .notdef box
        glm::vec2 position;  // the glyph's origin from the line's start on the baseline, pixels, y down
        std::uint32_t cluster;  // byte offset in `text` of the characters it draws
        float advance;          // how far the pen moves after it, pixels
    };
    struct Shaped {
        std::string text;  // the line as shaped: valid UTF-8 (malformed bytes became U+FFFD)
        std::vector<ShapedGlyph> glyphs;
        float width = 0;   // the pen's advance, pixels
    };
    Shaped shape(std::string_view utf8, std::string_view language = {}) const;

    // A glyph's ink box from its origin, pixels, y down (a "p" has
    // bottom > 0), hinted as it is drawn. Measured from its outline: no
    // bitmap is made, no atlas changes.
    struct Ink {
        float left = 0, right = 0, top = 0, bottom = 0;
        bool empty() const { return !(right > left && bottom > top); }
    };
    Ink ink(std::uint32_t face, unsigned index) const;

    // The faces shaped lines draw from: [0] is the font's own file, then
    // fallbacks in the order they were first needed.
    std::size_t face_count() const { return faces_.size(); }
    const FontFile& face_file(std::size_t face) const;

    // A glyph's 8-bit coverage bitmap as it is drawn (light hinting): its
    // top-left corner from the pen, y up (FreeType's bitmap_left and
    // bitmap_top), and rows `pitch` bytes apart (bottom-up when negative).
    // The rows are FreeType's: valid until this font's next rasterise() or ink().
    struct Bitmap {
        float left = 0, top = 0;
        int width = 0, height = 0, pitch = 0;
        const unsigned char* rows = nullptr;
    };
    Bitmap rasterise(std::uint32_t face, unsigned index) const;
    // The widest glyph face `face` may have at this size, pixels.
    float widest(std::uint32_t face) const;

    // A backend's own cache for this font, freed with it: the GL canvas
    // keeps its glyph atlas here (render/gl/text_gl.cpp).
    std::shared_ptr<void>& backend_cache() const { return backend_cache_; }

private:
    // One FreeType face at the font's size and its glyphs' ink boxes.
    struct Face {
        FontFile file;
        FT_FaceRec_* face = nullptr;
        std::unordered_map<unsigned, Ink> inks;  // by glyph index
        float widest = 0;
    };

    std::unique_ptr<Face> open_face(const FontFile& file) const;
    // The face to draw `c` from: the font's own when it has it, else the
    // fallback for `language`, else (no installed font has it) the font's
    // own, whose .notdef box is drawn, with a warning.
    std::uint32_t face_for(char32_t c, std::string_view language) const;

    float pixel_size_;
    std::string path_;
    FT_LibraryRec_* library_ = nullptr;
    float ascender_ = 0, descender_ = 0, line_height_ = 0, cap_height_ = 0;
    // Caches: filling them does not change what the font draws.
    mutable std::vector<std::unique_ptr<Face>> faces_;
    mutable std::map<std::pair<char32_t, std::string>, std::uint32_t> fallback_of_;
    // The lines shaped last, most recent first, by language and text: a
    // layout tried at many sizes (size_that_fits) measures the same titles
    // each time, and a 100,000-character one costs milliseconds to shape.
    struct Remembered {
        std::string language, utf8;
        Shaped shaped;
    };
    mutable std::vector<Remembered> remembered_;
    mutable std::mutex remembered_mutex_;  // shape() was safe to call from several threads for text the font has
    Shaped shape_anew(std::string_view utf8, std::string_view language) const;
    mutable std::shared_ptr<void> backend_cache_;
};

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

// Where a line of text may break, by the Unicode line-breaking algorithm:
// `paragraph` in lines no wider than `width` pixels in `font`, each line's
// trailing spaces dropped. A word wider than `width` stays whole, on a line
// of its own: callers compare the widest line with the room they have.
std::vector<std::string> wrap(const Font& font, std::string_view paragraph, float width,
                              std::string_view language = {});

// Characters no installed font has are drawn as the .notdef box and reported
// here once per process each, as a line such as "no installed font has
// U+E000 (in "...")". By default the line goes to standard error behind
// "figgen: warning: ".
void set_missing_glyph_warning(std::function<void(const std::string&)> warn);

// Where a line added to a Text with these arguments puts its ink: each
// glyph's ink box (from its outline, hinted as drawn), the upright
// rectangle around it when turned, and the box around them all. What a
// reader sees as text running into text: a line's advance and the font's
// ascender and descender leave room that most glyphs do not fill. Empty
// (box.w = 0) for a line with no ink. Shapes the line and rasterises
// nothing: a fit check leaves the glyph atlases as they were.
struct LineInk {
    Rect box;
    std::vector<Rect> glyphs;
    float em = 0;  // the font's size, pixels
};
LineInk line_ink(const Font& font, std::string_view utf8, glm::vec2 position, Align align = Align::left,
                 Baseline baseline = Baseline::baseline, float rotation_degrees = 0, std::string_view language = {});

// A batch of strings, drawn with one draw call per font. The fonts must
// outlive the batch's last draw().
class Text {
public:
    // `position` is the anchor named by align and baseline; the line turns
    // `rotation_degrees` counter-clockwise on screen about it (90 for a
    // y-axis label, reading bottom to top).
    void add(Font& font, std::string_view utf8, glm::vec2 position, const glm::vec4& colour,
             Align align = Align::left, Baseline baseline = Baseline::baseline, float rotation_degrees = 0,
             std::string_view language = {});

    bool empty() const { return lines_.empty(); }
    void clear() { lines_.clear(); }
    // Draws every line on `surface` (render/surface.hpp).
    void draw(Surface& surface) const;

    // Each line as laid out, which a backend draws: the GL canvas as quads
    // from its glyph atlas, the vector page as the glyphs' outlines.
    struct Line {
        const Font* font;
        glm::vec2 origin;        // the pen's start on the baseline, pixels
        float rotation_degrees;  // counter-clockwise on screen about the origin
        glm::vec4 colour;
        Font::Shaped shaped;     // the glyphs, their faces and positions from the origin, and the text
    };
    const std::vector<Line>& lines() const { return lines_; }

private:
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
