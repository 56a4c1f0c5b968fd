// render::wrap against the rule it implements, measured piece by piece as
// it once was; any code point through it; long text in O(n log n).
#include <catch2/catch.hpp>

#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "render/line_break.hpp"
#include "render/text.hpp"
#include "base/utf8.hpp"

using render::Font;

namespace {

// The greedy rule, measured as wrap measured it before it was made
// O(n log n): at every break, the whole line so far shaped again; a line
// ends at the last break before the first piece that does not fit, or at
// a mandatory break.
std::vector<std::string> wrap_by_every_piece(const Font& font, const std::string& paragraph, float width,
                                             const std::string& language = "") {
    const std::string text = font.shape(paragraph, language).text;
    const std::u32string codepoints = base::decode_utf8(text);
    const std::vector<render::LineBreak> breaks = render::line_breaks(codepoints, language);
    auto trimmed = [](std::string line) {
        while (!line.empty() && (line.back() == ' ' || line.back() == '\n')) line.pop_back();
        return line;
    };
    std::vector<std::string> lines;
    std::size_t start = 0, fits = std::string::npos, end = 0;
    for (std::size_t i = 0; i < codepoints.size(); ++i) {
        end += base::encode_utf8(codepoints[i]).size();
        if (breaks[i] == render::LineBreak::none) continue;
        if (fits != std::string::npos && font.width(trimmed(text.substr(start, end - start)), language) > width) {
            lines.push_back(trimmed(text.substr(start, fits - start)));
            start = fits;
        }
        fits = end;
        if (breaks[i] == render::LineBreak::must) {
            lines.push_back(trimmed(text.substr(start, end - start)));
            start = end;
            fits = std::string::npos;
        }
    }
    if (start < text.size()) lines.push_back(trimmed(text.substr(start)));
    return lines;
}

// Characters no font has (flags, tags, noncharacters) are not reported while it lives.
struct QuietMissingGlyphs {
    QuietMissingGlyphs() { render::set_missing_glyph_warning([](const std::string&) {}); }
    ~QuietMissingGlyphs() {
        render::set_missing_glyph_warning(
            [](const std::string& line) { std::fprintf(stderr, "figgen: warning: %s\n", line.c_str()); });
    }
};

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

TEST_CASE("wrap breaks where measuring every piece did, at every width", "[text][wrap]") {
    const QuietMissingGlyphs quiet;
    Font font(15);
    const std::vector<std::pair<std::string, std::string>> paragraphs = {
        {"Gray-Scott, f = 0.035, k = 0.057: spots split and fill the dish (Pearson's type alpha); "
         "AVAVAV WA To Ty yo, a supercalifragilisticexpialidocious word and a\nline feed.", ""},
        {"雪花是自然界的生长现象，它具有复杂的树枝状形态。\n“雪花”的生长：扩散限制凝聚。", "zh-cn"},
        {"雪の結晶は、中谷宇吉郎によって「天から送られた手紙」と呼ばれた。", "ja"},
        {"مرحبا بالعالم، هذا نص عربي للاختبار mixed with English words", ""},
        {"\xF0\x9F\x87\xBA\xF0\x9F\x87\xB8 \xF0\x9F\x87\xAB\xF0\x9F\x87\xB7 flags \xF0\x9F\x87\xAF\xF0\x9F\x87\xB5"
         "\xF0\x9F\x87\xA9\xF0\x9F\x87\xAA side by side", ""},
        {"   leading spaces, trailing   \n\n  and empty lines  ", ""},
    };
    for (const auto& [paragraph, language] : paragraphs) {
        for (float width = 8; width < 700; width += 13) {
            INFO(paragraph << " at " << width << " px");
            CHECK(render::wrap(font, paragraph, width, language) == wrap_by_every_piece(font, paragraph, width, language));
        }
    }
    // Known lines: a word wider than the room alone on its line, a line feed kept as a break.
    CHECK(render::wrap(font, "a supercalifragilistic b", 40) == std::vector<std::string>{"a", "supercalifragilistic", "b"});
    CHECK(render::wrap(font, "one two\nthree", 1000) == std::vector<std::string>{"one two", "three"});
}

TEST_CASE("flags, noncharacters, tags, surrogates and controls go through wrap as drawn", "[text][wrap]") {
    const QuietMissingGlyphs quiet;
    Font font(15);
    // Each code point of the kinds libunibreak mishandled or might: regional
    // indicators, noncharacters, tags, specials, C0 and C1 controls, and
    // bytes that are no UTF-8 (surrogates, above U+10FFFF), between letters.
    std::vector<char32_t> codes;
    for (char32_t c = 0x1F1E6; c <= 0x1F1FF; ++c) codes.push_back(c);
    for (char32_t c = 0xFDD0; c <= 0xFDEF; ++c) codes.push_back(c);
    for (char32_t plane = 0; plane <= 0x10; ++plane) {
        codes.push_back(plane << 16 | 0xFFFE);
        codes.push_back(plane << 16 | 0xFFFF);
    }
    for (char32_t c = 0xE0000; c <= 0xE007F; ++c) codes.push_back(c);
    for (char32_t c = 0xFFF0; c <= 0xFFFD; ++c) codes.push_back(c);
    for (char32_t c = 0; c < 0xA0; ++c)
        if (c < 0x20 || c >= 0x7F) codes.push_back(c);
    std::string text;
    for (const char32_t c : codes) text += "ab " + base::encode_utf8(c) + base::encode_utf8(c) + " ";
    text += "\xED\xA0\x80 \xF4\x90\x80\x80 \xFF";  // U+D800 and U+110000 as UTF-8 would write them, a stray byte
    for (const float width : {1.0f, 30.0f, 300.0f, 3000.0f}) {
        const std::vector<std::string> lines = render::wrap(font, text, width);
        REQUIRE_FALSE(lines.empty());
        // Nothing but spaces and line breaks is lost: the flags' bytes are still there.
        std::string all;
        for (const std::string& line : lines) all += line;
        CHECK(all.find("\xF0\x9F\x87\xBA\xF0\x9F\x87\xBA") != std::string::npos);  // U+1F1FA twice
        CHECK(lines == wrap_by_every_piece(font, text, width));
    }
}

TEST_CASE("shaping and wrapping 100,000 characters take well under a second of CPU", "[text][wrap]") {
    Font font(15);
    std::string text;
    while (text.size() < 100000) text += "lorem ipsum dolor sit amet ";
    text.resize(100000);
    double start = cpu_seconds();
    const Font::Shaped shaped = font.shape(text);
    const double shaping = cpu_seconds() - start;
    CHECK(shaped.glyphs.size() == 100000);
    CHECK(shaped.glyphs[99999].cluster == 99999);  // a byte offset, as for short text
    // raqm 0.7 given UTF-8 took minutes here (each cluster converted from the text's start).
    CHECK(shaping < 1.0);
    start = cpu_seconds();
    const std::vector<std::string> lines = render::wrap(font, text, 884);
    const double wrapping = cpu_seconds() - start;
    // 884 px hold some 117 characters of this text at 15 px: about 855 lines.
    CHECK(lines.size() > 700);
    CHECK(lines.size() < 1000);
    for (const std::string& line : lines) CHECK(font.width(line) <= 884);
    // Measuring every piece from its line's start took about 15 s here.
    CHECK(wrapping < 1.5);
}
