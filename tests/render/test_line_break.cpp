// render::line_breaks: libunibreak made safe for every code point, and the
// breaks it gives where UAX #14 says what they are.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "render/line_break.hpp"

using render::LineBreak;

namespace {

// Every code point, surrogates and noncharacters too, each between two
// copies of `neighbour` (0: beside its own neighbours in code point order,
// doubled: each twice). With `sparse`, planes 4 to 13 (0x40000 to 0xDFFFF,
// 58% of the code points), where Unicode assigns nothing and UAX #14 gives
// every code point the one class XX, are sampled every 97th: the neighbour
// passes take half the time, and the doubled pass of each language still
// holds every code point.
std::u32string every_code_point(char32_t neighbour, bool doubled = false, bool sparse = false) {
    std::u32string text;
    text.reserve(3 * 0x110000);
    for (char32_t c = 0; c <= 0x10FFFF; ++c) {
        if (sparse && c >= 0x40000 && c <= 0xDFFFF && c % 97 != 0) continue;
        if (neighbour) text += neighbour;
        text += c;
        if (doubled) text += c;
    }
    if (neighbour) text += neighbour;
    return text;
}

}  // namespace

TEST_CASE("the breaker's stand-ins: regional indicators as a letter, noncharacters as U+FFFD", "[text][line_break]") {
    CHECK(render::line_break_stand_in(0x1F1E6) == U'A');  // regional indicator A
    CHECK(render::line_break_stand_in(0x1F1FA) == U'A');  // U, as in the flag U+1F1FA U+1F1F8
    CHECK(render::line_break_stand_in(0x1F1FF) == U'A');
    CHECK(render::line_break_stand_in(0xFFFF) == U'\uFFFD');
    CHECK(render::line_break_stand_in(0xFFFE) == U'\uFFFD');
    CHECK(render::line_break_stand_in(0xFDD0) == U'\uFFFD');
    CHECK(render::line_break_stand_in(0x10FFFF) == U'\uFFFD');
    CHECK(render::line_break_stand_in(0xD800) == U'\uFFFD');   // a surrogate is no character either
    CHECK(render::line_break_stand_in(0x110000) == U'\uFFFD');
    // Everything else is itself: letters, the code points beside the ranges, tags.
    for (const char32_t c : {char32_t(U'a'), char32_t(0x1F1E5), char32_t(0x1F200), char32_t(0xFFFD), char32_t(0xFDCF),
                             char32_t(0xFDF0), char32_t(0xE0041), char32_t(0x4E00), char32_t(0)})
        CHECK(render::line_break_stand_in(c) == c);
}

TEST_CASE("line breaks follow UAX #14 for spaces, line feeds, ideographs and flags", "[text][line_break]") {
    CHECK(render::line_breaks(U"") .empty());
    CHECK(render::line_breaks(U"a b") == std::vector<LineBreak>{LineBreak::none, LineBreak::allow, LineBreak::must});
    CHECK(render::line_breaks(U"a\nb") == std::vector<LineBreak>{LineBreak::none, LineBreak::must, LineBreak::must});
    // Ideographs break between any two, not before a closing mark.
    CHECK(render::line_breaks(U"雪花。") == std::vector<LineBreak>{LineBreak::allow, LineBreak::none, LineBreak::must});
    // Two flags (US, FR) with a space: each flag whole, a break after the space.
    CHECK(render::line_breaks(U"\U0001F1FA\U0001F1F8 \U0001F1EB\U0001F1F7") ==
          std::vector<LineBreak>{LineBreak::none, LineBreak::none, LineBreak::allow, LineBreak::none, LineBreak::must});
    // U+FFFF, which libunibreak took for the text's end, breaks as U+FFFD.
    CHECK(render::line_breaks(U"a \uFFFF b") == render::line_breaks(U"a \uFFFD b"));
}

// Debian 12's libunibreak aborted on U+FFFF and the regional indicators
// ("set_linebreaks: Assertion 'lbcNew <= LBP_JT' failed"): this process
// would die here if any code point, alone or beside any of these, still did.
TEST_CASE("every code point goes through the line breaker, alone and beside others, in every language",
          "[text][line_break]") {
    const std::vector<char32_t> neighbours = {0,      U'a',   U' ',   U'1',   U'(',    U')',    U'-',
                                              U'\n',  0x4E00, 0x0301, 0x200B, 0x2060,  0xAC00,  0x1100,
                                              0x11A8, 0x0E01, 0xFFFC, 0x3002, 0x05D0,  0x1F1FA, 0xFFFF};
    // The languages tailor the classes of ideographs, punctuation and
    // combining marks: each of them beside those, with the language-free
    // pass beside every neighbour above.
    const std::vector<char32_t> tailored = {0, U'(', U')', 0x4E00, 0x0301, 0x3002, 0xFFFC, 0xFFFF, 0x1F1FA};
    for (const char* language : {"", "ja", "zh-cn", "ko"}) {
        for (const char32_t neighbour : *language ? tailored : neighbours) {
            INFO("language \"" << language << "\", neighbour U+" << std::hex << unsigned(neighbour));
            const std::u32string text = every_code_point(neighbour, false, true);
            const std::vector<LineBreak> breaks = render::line_breaks(text, language);
            REQUIRE(breaks.size() == text.size());
            CHECK(breaks.back() == LineBreak::must);
            // A line feed ends its line wherever it is.
            std::size_t feeds = 0, forced = 0;
            for (std::size_t i = 0; i < text.size(); ++i)
                if (text[i] == U'\n') {
                    ++feeds;
                    forced += breaks[i] == LineBreak::must;
                }
            CHECK(forced == feeds);
        }
        const std::u32string doubled = every_code_point(0, true);
        CHECK(render::line_breaks(doubled, language).size() == doubled.size());
    }
}
