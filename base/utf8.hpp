#pragma once
// UTF-8 to code points, for text drawing. Figure labels come from TOML files
// (UTF-8 by definition) and from C++ string literals (UTF-8 with GCC/Clang).

#include <cstddef>
#include <string>
#include <string_view>

namespace base {

// The replacement character, drawn wherever the input is not valid UTF-8.
inline constexpr char32_t replacement_character = U'\uFFFD';

// The character that starts at utf8[at] (at < size): its code point and
// its length in bytes when it is valid UTF-8; else U+FFFD, valid = false,
// and the bytes a decoder skips (the lead and the continuation bytes after
// it, up to the sequence's length). The one decoder every reader uses.
struct Utf8Char {
    char32_t code;
    std::size_t length;
    bool valid;
};
Utf8Char decode_utf8_at(std::string_view utf8, std::size_t at);

// Decodes `utf8`; each malformed sequence (stray continuation byte, truncated
// sequence, overlong form, surrogate, value above U+10FFFF) becomes one
// U+FFFD and decoding resumes at the next byte that could start a sequence.
std::u32string decode_utf8(std::string_view utf8);

// Code point `c` (below 0x110000) in UTF-8 as it is, surrogates and
// noncharacters too: what a careless writer would put in a file.
std::string encode_utf8(char32_t c);

}  // namespace base
