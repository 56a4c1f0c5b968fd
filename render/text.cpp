#include "render/text.hpp"

#include <map>
#include <memory>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <mutex>
#include <set>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_TRUETYPE_TABLES_H
#include <hb.h>
#include <raqm.h>

#include "render/line_break.hpp"
#include "base/utf8.hpp"

namespace render {
namespace {

std::string freetype_error(FT_Error error) {
    const char* text = FT_Error_String(error);  // null unless FreeType was built with error strings
    return text ? text : "FreeType error " + std::to_string(error);
}


}  // namespace

namespace {

std::function<void(const std::string&)>& missing_glyph_warning() {
    static std::function<void(const std::string&)> warn = [](const std::string& line) {
        std::fprintf(stderr, "figgen: warning: %s\n", line.c_str());
    };
    return warn;
}

std::string codepoint_name(char32_t c) {
    char name[16];
    std::snprintf(name, sizeof name, "U+%04lX", static_cast<unsigned long>(c));
    return name;
}

// Characters that take the face of the character before them: combining
// marks, joiners and variation selectors belong to their base's cluster.
bool follows_base(char32_t c) {
    switch (hb_unicode_general_category(hb_unicode_funcs_get_default(), c)) {
        case HB_UNICODE_GENERAL_CATEGORY_NON_SPACING_MARK:
        case HB_UNICODE_GENERAL_CATEGORY_SPACING_MARK:
        case HB_UNICODE_GENERAL_CATEGORY_ENCLOSING_MARK:
        case HB_UNICODE_GENERAL_CATEGORY_FORMAT: return true;
        default: return (c >= 0xFE00 && c <= 0xFE0F) || (c >= 0xE0100 && c <= 0xE01EF);
    }
}

// Characters nothing is drawn for, so no font needs to have them.
bool invisible(char32_t c) {
    return c < 0x20 || (c >= 0x7F && c < 0xA0) || follows_base(c) ||
           hb_unicode_general_category(hb_unicode_funcs_get_default(), c) == HB_UNICODE_GENERAL_CATEGORY_LINE_SEPARATOR;
}

struct RaqmDeleter {
    void operator()(raqm_t* rq) const { raqm_destroy(rq); }
};

}  // namespace

void set_missing_glyph_warning(std::function<void(const std::string&)> warn) {
    missing_glyph_warning() = std::move(warn);
}

Font::Font(float pixel_size, const std::string& path) : pixel_size_(pixel_size), path_(path) {
    if (!(pixel_size > 0)) throw std::invalid_argument("font pixel size must be positive, got " + std::to_string(pixel_size));
    if (const FT_Error error = FT_Init_FreeType(&library_))
        throw std::runtime_error("cannot start FreeType for font " + path + ": " + freetype_error(error));
    try {
        faces_.push_back(open_face(FontFile{path, 0}));
    } catch (...) {
        FT_Done_FreeType(library_);
        throw;
    }
    FT_Face face = faces_[0]->face;
    // Metrics from font units rather than face->size->metrics, which FreeType
    // rounds to whole pixels.
    const float scale = static_cast<float>(std::lround(pixel_size * 64)) / 64.0f / static_cast<float>(face->units_per_EM);
    ascender_ = static_cast<float>(face->ascender) * scale;
    descender_ = static_cast<float>(face->descender) * scale;
    line_height_ = static_cast<float>(face->height) * scale;
    const auto* os2 = static_cast<const TT_OS2*>(FT_Get_Sfnt_Table(face, FT_SFNT_OS2));
    if (os2 && os2->version >= 2 && os2->sCapHeight > 0) {
        cap_height_ = static_cast<float>(os2->sCapHeight) * scale;
    } else if (FT_Load_Char(face, 'H', FT_LOAD_NO_SCALE) == 0) {  // older tables: measure the letter itself
        cap_height_ = static_cast<float>(face->glyph->metrics.horiBearingY) * scale;
    } else {
        cap_height_ = 0.7f * pixel_size;
    }
}

Font::~Font() {
    for (auto& f : faces_) FT_Done_Face(f->face);
    FT_Done_FreeType(library_);
}

std::unique_ptr<Font::Face> Font::open_face(const FontFile& file) const {
    auto f = std::make_unique<Face>();
    f->file = file;
    if (const FT_Error error = FT_New_Face(library_, file.path.c_str(), file.index, &f->face))
        throw std::runtime_error("cannot load font " + file.path + ": " + freetype_error(error));
    // Fractional sizes are fine: 26.6 fixed point at 72 dpi is pixels.
    const auto size_26_6 = static_cast<FT_F26Dot6>(std::lround(pixel_size_ * 64));
    if (!FT_IS_SCALABLE(f->face) || FT_Set_Char_Size(f->face, 0, size_26_6, 72, 72) != 0) {
        FT_Done_Face(f->face);
        throw std::runtime_error("font " + file.path + " cannot be scaled to " + std::to_string(pixel_size_) + " px");
    }
    const float scale = static_cast<float>(size_26_6) / 64.0f / static_cast<float>(f->face->units_per_EM);
    f->widest = static_cast<float>(f->face->bbox.xMax - f->face->bbox.xMin) * scale;
    return f;
}

const FontFile& Font::face_file(std::size_t face) const { return faces_.at(face)->file; }

std::uint32_t Font::face_for(char32_t c, std::string_view language) const {
    if (FT_Get_Char_Index(faces_[0]->face, c) != 0 || invisible(c)) return 0;
    const auto key = std::make_pair(c, std::string(language));
    if (const auto found = fallback_of_.find(key); found != fallback_of_.end()) return found->second;
    std::uint32_t face = 0;
    if (const std::optional<FontFile> file = fallback_font(c, language)) {
        const auto known = std::find_if(faces_.begin(), faces_.end(), [&](const auto& f) { return f->file == *file; });
        face = static_cast<std::uint32_t>(known - faces_.begin());
        if (known == faces_.end()) faces_.push_back(open_face(*file));
        if (FT_Get_Char_Index(faces_[face]->face, c) == 0) face = 0;  // fontconfig's charset and the face disagree
    }
    if (face == 0) {
        // Once a process: the font cache is cleared before each figure.
        static std::mutex mutex;
        static std::set<char32_t> reported;
        const std::lock_guard lock(mutex);
        if (reported.insert(c).second)
            missing_glyph_warning()("no installed font has " + codepoint_name(c) + "; it is drawn as an empty box");
    }
    fallback_of_.emplace(key, face);
    return face;
}

float Font::width(std::string_view utf8, std::string_view language) const { return shape(utf8, language).width; }

Font::Shaped Font::shape(std::string_view utf8, std::string_view language) const {
    constexpr std::size_t most_remembered = 16;
    {
        const std::lock_guard lock(remembered_mutex_);
        const auto found = std::find_if(remembered_.begin(), remembered_.end(), [&](const Remembered& r) {
            return r.utf8.size() == utf8.size() && r.language == language && r.utf8 == utf8;
        });
        if (found != remembered_.end()) {
            std::rotate(remembered_.begin(), found, found + 1);  // now the most recent
            return remembered_.front().shaped;
        }
    }
    Shaped out = shape_anew(utf8, language);
    const std::lock_guard lock(remembered_mutex_);
    if (remembered_.size() == most_remembered) remembered_.pop_back();
    remembered_.insert(remembered_.begin(), Remembered{std::string(language), std::string(utf8), out});
    return out;
}

Font::Shaped Font::shape_anew(std::string_view utf8, std::string_view language) const {
    Shaped out;
    const std::u32string codepoints = base::decode_utf8(utf8);
    if (codepoints.empty()) return out;
    // Valid UTF-8 for the caller, where each character starts in it, and
    // each character's face: runs of one face are shaped together.
    std::vector<std::size_t> byte_of(codepoints.size() + 1);  // code point index -> byte offset in out.text
    std::vector<std::pair<std::size_t, std::uint32_t>> runs;  // code point index where a run starts, its face
    for (std::size_t i = 0; i < codepoints.size(); ++i) {
        const char32_t c = codepoints[i];
        const std::uint32_t face = (i > 0 && follows_base(c)) ? runs.back().second : face_for(c, language);
        if (runs.empty() || runs.back().second != face) runs.emplace_back(i, face);
        byte_of[i] = out.text.size();
        out.text += base::encode_utf8(c);
    }
    byte_of[codepoints.size()] = out.text.size();
    // raqm is given code points, not UTF-8: for UTF-8 text raqm 0.7 turns
    // each glyph's cluster back into a byte offset by converting the whole
    // text before it, which made shaping quadratic in the text's length
    // (20,000 characters took minutes). Its layout is the same either way.
    std::unique_ptr<raqm_t, RaqmDeleter> rq(raqm_create());
    static_assert(sizeof(char32_t) == sizeof(std::uint32_t));
    if (!rq || !raqm_set_text(rq.get(), reinterpret_cast<const std::uint32_t*>(codepoints.data()), codepoints.size()) ||
        !raqm_set_par_direction(rq.get(), RAQM_DIRECTION_DEFAULT))
        throw std::runtime_error("raqm cannot take the text \"" + out.text + "\"");
    if (!language.empty()) {
        const std::string tag(language);
        raqm_set_language(rq.get(), tag.c_str(), 0, codepoints.size());
    }
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const std::size_t end = r + 1 < runs.size() ? runs[r + 1].first : codepoints.size();
        if (!raqm_set_freetype_face_range(rq.get(), faces_[runs[r].second]->face, runs[r].first, end - runs[r].first))
            throw std::runtime_error("raqm cannot take a face for \"" + out.text + "\"");
    }
    // Unhinted advances (FreeType's linear ones): the pen keeps fractional
    // positions, so spacing stays true at every size.
    raqm_set_freetype_load_flags(rq.get(), FT_LOAD_NO_HINTING);
    if (!raqm_layout(rq.get())) throw std::runtime_error("raqm cannot lay out \"" + out.text + "\"");
    std::size_t count = 0;
    const raqm_glyph_t* glyphs = raqm_get_glyphs(rq.get(), &count);
    out.glyphs.reserve(count);
    float pen = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const raqm_glyph_t& g = glyphs[i];
        std::uint32_t face = 0;
        while (face < faces_.size() && faces_[face]->face != g.ftface) ++face;
        if (face == faces_.size()) throw std::runtime_error("raqm gave a glyph of a face the font does not hold");
        const std::size_t cluster = std::min<std::size_t>(g.cluster, codepoints.size());
        out.glyphs.push_back({face, g.index,
                              {pen + static_cast<float>(g.x_offset) / 64.0f, -static_cast<float>(g.y_offset) / 64.0f},
                              static_cast<std::uint32_t>(byte_of[cluster]), static_cast<float>(g.x_advance) / 64.0f});
        pen += static_cast<float>(g.x_advance) / 64.0f;
    }
    out.width = pen;
    return out;
}

Font::Bitmap Font::rasterise(std::uint32_t face, unsigned index) const {
    Face& f = *faces_.at(face);
    // Light hinting snaps only vertically (baseline, x-height), which keeps
    // the unhinted advances below true; the bitmap is 8-bit grey coverage.
    if (const FT_Error error = FT_Load_Glyph(f.face, index, FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT))
        throw std::runtime_error("cannot render glyph " + std::to_string(index) + " of " + f.file.path + ": " +
                                 freetype_error(error));
    const FT_GlyphSlot slot = f.face->glyph;
    const FT_Bitmap& bitmap = slot->bitmap;
    if (bitmap.pixel_mode != FT_PIXEL_MODE_GRAY && bitmap.rows > 0)
        throw std::runtime_error("font " + f.file.path + " gave a glyph bitmap that is not 8-bit grey");
    Bitmap out;
    out.left = static_cast<float>(slot->bitmap_left);
    out.top = static_cast<float>(slot->bitmap_top);
    out.width = static_cast<int>(bitmap.width);
    out.height = static_cast<int>(bitmap.rows);
    out.pitch = bitmap.pitch;
    out.rows = bitmap.buffer;
    return out;
}

float Font::widest(std::uint32_t face) const { return faces_.at(face)->widest; }

Font::Ink Font::ink(std::uint32_t face, unsigned index) const {
    Face& f = *faces_[face];
    if (const auto found = f.inks.find(index); found != f.inks.end()) return found->second;
    // rasterise()'s hinting, without its bitmap.
    if (const FT_Error error = FT_Load_Glyph(f.face, index, FT_LOAD_TARGET_LIGHT))
        throw std::runtime_error("cannot load glyph " + std::to_string(index) + " of " + f.file.path + ": " +
                                 freetype_error(error));
    const FT_Glyph_Metrics& m = f.face->glyph->metrics;  // 26.6 fixed point, y up
    const Ink ink{static_cast<float>(m.horiBearingX) / 64.0f, static_cast<float>(m.horiBearingX + m.width) / 64.0f,
                  -static_cast<float>(m.horiBearingY) / 64.0f, static_cast<float>(m.height - m.horiBearingY) / 64.0f};
    return f.inks.emplace(index, ink).first->second;
}

std::vector<std::string> wrap(const Font& font, std::string_view paragraph, float width, std::string_view language) {
    const Font::Shaped whole = font.shape(paragraph, language);
    const std::string& text = whole.text;  // valid UTF-8
    // The places a line may end: the byte after each character that allows
    // or forces a break.
    struct Candidate {
        std::size_t end;
        bool must;
    };
    std::vector<Candidate> candidates;
    {
        const std::u32string codepoints = base::decode_utf8(text);
        const std::vector<LineBreak> breaks = line_breaks(codepoints, language);
        std::size_t end = 0;
        for (std::size_t i = 0; i < codepoints.size(); ++i) {
            end += base::encode_utf8(codepoints[i]).size();
            if (breaks[i] != LineBreak::none) candidates.push_back({end, breaks[i] == LineBreak::must});
        }
    }
    auto trimmed_end = [&](std::size_t start, std::size_t end) {
        while (end > start && (text[end - 1] == ' ' || text[end - 1] == '\n')) --end;
        return end;
    };
    auto piece = [&](std::size_t start, std::size_t end) { return text.substr(start, trimmed_end(start, end) - start); };
    // The pen's advance before each byte, the paragraph shaped in one piece:
    // a line's width but for the kerning and joining at its two ends, which
    // says where to look for its end.
    std::vector<double> advance_before(text.size() + 1, 0.0);
    for (const Font::ShapedGlyph& g : whole.glyphs)
        if (g.cluster < text.size()) advance_before[g.cluster + 1] += g.advance;
    for (std::size_t i = 1; i < advance_before.size(); ++i) advance_before[i] += advance_before[i - 1];

    std::vector<std::string> lines;
    std::size_t start = 0;  // where the line being filled starts
    auto overflows = [&](std::size_t k) { return font.width(piece(start, candidates[k].end), language) > width; };
    auto guessed_over = [&](std::size_t k) {
        return advance_before[trimmed_end(start, candidates[k].end)] - advance_before[start] > width;
    };
    // Each line takes the pieces up to the last break before the first that
    // does not fit (a piece wider than the room stays whole, alone on its
    // line), or up to a mandatory break. A longer piece of a line is no
    // narrower, so that first break is found by measuring two or three
    // pieces, not every one: the paragraph's own advances say where it
    // is, to within a kerning pair, and the pieces shaped on their own
    // (as each line is drawn) decide, galloping away from the guess until
    // the break is bracketed, then halving. Measuring every piece from the
    // line's start was quadratic in the paragraph's length.
    std::size_t k = 0;
    while (k < candidates.size()) {
        if (candidates[k].must) {  // the line's first piece, whole, and its end
            lines.push_back(piece(start, candidates[k].end));
            start = candidates[k].end;
            ++k;
            continue;
        }
        // The last candidate this line may reach: its mandatory break, or the text's last break.
        std::size_t last = k + 1;
        while (last < candidates.size() && !candidates[last].must) ++last;
        if (last == candidates.size()) --last;
        if (last == k) break;  // the first piece is the text's last: the rest below
        // The guess: the first candidate whose piece overflows by the paragraph's advances (last + 1: none).
        std::size_t low = k + 1, high = last + 1;
        while (low < high) {
            const std::size_t middle = low + (high - low) / 2;
            if (guessed_over(middle)) high = middle;
            else low = middle + 1;
        }
        // fitted: a candidate known to fit (the first piece always does); over: one known to overflow.
        std::size_t fitted = k, over = candidates.size();
        if (low - 1 > k) {
            if (overflows(low - 1)) {  // the guess was late: gallop back
                over = low - 1;
                for (std::size_t step = 1; over - fitted > 1; step *= 2) {
                    const std::size_t probe = over - std::min(step, over - fitted - 1);
                    if (!overflows(probe)) {
                        fitted = probe;
                        break;
                    }
                    over = probe;
                }
            } else {
                fitted = low - 1;
            }
        }
        for (std::size_t step = 1; over == candidates.size() && fitted < last; step *= 2) {  // gallop on
            const std::size_t probe = std::min(fitted + step, last);
            if (overflows(probe)) over = probe;
            else fitted = probe;
        }
        if (over == candidates.size()) {  // everything up to `last` fits
            if (candidates[last].must) {
                lines.push_back(piece(start, candidates[last].end));
                start = candidates[last].end;
            }
            k = last + 1;
            continue;
        }
        while (over - fitted > 1) {  // halve: fitted fits, over overflows
            const std::size_t middle = fitted + (over - fitted) / 2;
            (overflows(middle) ? over : fitted) = middle;
        }
        lines.push_back(piece(start, candidates[fitted].end));  // break at the last that fitted
        start = candidates[fitted].end;
        k = over;  // the next line's first piece
    }
    if (start < text.size()) lines.push_back(piece(start, text.size()));
    return lines;
}

namespace {

// Where the pen starts, on the page, for a line `width` pixels wide
// anchored at `position` by align and baseline and turned by `rotate`.
glm::vec2 line_origin(const Font& font, float width, glm::vec2 position, Align align, Baseline baseline,
                      const Rotation& rotate) {
    // The pen's start in the line's own frame (x along the baseline, y down), relative to the anchor.
    glm::vec2 start{0, 0};
    if (align == Align::centre) start.x = -width / 2;
    if (align == Align::right) start.x = -width;
    switch (baseline) {
        case Baseline::top: start.y = font.ascender(); break;
        case Baseline::middle: start.y = font.cap_height() / 2; break;
        case Baseline::baseline: break;
        case Baseline::bottom: start.y = font.descender(); break;
    }
    glm::vec2 origin = position + rotate(start);
    // Glyphs are hinted to whole pixels vertically: put the baseline on a
    // pixel edge too, or filtering blurs the crisp rows. Along the baseline
    // the pen keeps its fractional position, so spacing stays true.
    if (rotate.s == 0) origin.y = std::round(origin.y);
    if (rotate.c == 0) origin.x = std::round(origin.x);
    return origin;
}

}  // namespace

LineInk line_ink(const Font& font, std::string_view utf8, glm::vec2 position, Align align, Baseline baseline,
                 float rotation_degrees, std::string_view language) {
    const Font::Shaped shaped = font.shape(utf8, language);
    const Rotation rotate(rotation_degrees);
    const glm::vec2 origin = line_origin(font, shaped.width, position, align, baseline, rotate);
    LineInk out{{position.x, position.y, 0, 0}, {}, font.pixel_size()};
    constexpr float inf = std::numeric_limits<float>::infinity();
    glm::vec2 all_lo{inf}, all_hi{-inf};
    for (const Font::ShapedGlyph& g : shaped.glyphs) {
        const Font::Ink ink = font.ink(g.face, g.index);
        if (ink.empty()) continue;  // a space
        // The ink box's corners in the line's own frame (y down), turned onto the page.
        glm::vec2 lo{inf}, hi{-inf};
        for (const glm::vec2 corner : {glm::vec2{ink.left, ink.top}, glm::vec2{ink.right, ink.top},
                                       glm::vec2{ink.left, ink.bottom}, glm::vec2{ink.right, ink.bottom}}) {
            const glm::vec2 p = origin + rotate(g.position + corner);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        out.glyphs.push_back({lo.x, lo.y, hi.x - lo.x, hi.y - lo.y});
        all_lo = glm::min(all_lo, lo);
        all_hi = glm::max(all_hi, hi);
    }
    if (!out.glyphs.empty()) out.box = {all_lo.x, all_lo.y, all_hi.x - all_lo.x, all_hi.y - all_lo.y};
    return out;
}

void Text::add(Font& font, std::string_view utf8, glm::vec2 position, const glm::vec4& colour, Align align,
               Baseline baseline, float rotation_degrees, std::string_view language) {
    Font::Shaped shaped = font.shape(utf8, language);
    if (shaped.glyphs.empty()) return;
    const Rotation rotate(rotation_degrees);
    const glm::vec2 origin = line_origin(font, shaped.width, position, align, baseline, rotate);

    lines_.push_back(Line{&font, origin, rotation_degrees, colour, std::move(shaped)});
}

void Text::draw(Surface& surface) const {
    if (!lines_.empty()) surface.text(*this);
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
