#pragma once
// Where a line may break, by the Unicode line-breaking algorithm (UAX #14)
// as libunibreak implements it, made safe for every code point.
//
// Debian 12's libunibreak (its linebreak.h says version 2.2) asserts, and so
// aborts the process, on two kinds of code point: the regional indicators
// U+1F1E6..U+1F1FF (the letters of flag emoji), whose class its pair table
// lacks, and U+FFFF, which it takes for the end of the text. Testing every
// code point 0..U+10FFFF alone and beside letters, spaces, digits,
// brackets, ideographs, Hangul, Thai, combining marks and itself found no
// other (tests/render/test_line_break.cpp repeats that). Those are handed to
// the breaker as stand-ins that break as they should (a regional indicator
// as a letter: a flag stays whole; a noncharacter as U+FFFD); the text that
// is shaped and drawn is unchanged.

#include <string>
#include <string_view>
#include <vector>

namespace render {

enum class LineBreak : char {
    must,   // a line ends after this character (a line feed, the text's end)
    allow,  // a line may end after it
    none,   // the next character stays on its line
};

// What libunibreak is given for `c`: `c` itself, or its stand-in.
char32_t line_break_stand_in(char32_t c);

// For each code point of `text` (any code points, even surrogates and
// values above U+10FFFF, which break as U+FFFD), whether a line may end
// after it. `language`: a fontconfig tag ("ja", "zh-cn") or empty.
std::vector<LineBreak> line_breaks(std::u32string_view text, std::string_view language = {});

}  // namespace render
