#pragma once
// UTF-8 to code points, for text drawing. Figure labels come from TOML files
// (UTF-8 by definition) and from C++ string literals (UTF-8 with GCC/Clang).

#include <string>
#include <string_view>

namespace render {

// The replacement character, drawn wherever the input is not valid UTF-8.
inline constexpr char32_t replacement_character = U'\uFFFD';

// Decodes `utf8`; each malformed sequence (stray continuation byte, truncated
// sequence, overlong form, surrogate, value above U+10FFFF) becomes one
// U+FFFD and decoding resumes at the next byte that could start a sequence.
std::u32string decode_utf8(std::string_view utf8);

// Code point `c` (below 0x110000) in UTF-8 as it is, surrogates and
// noncharacters too: what a careless writer would put in a file.
std::string encode_utf8(char32_t c);

}  // namespace render
