#include "base/utf8.hpp"

namespace base {
namespace {

bool is_continuation(unsigned char byte) { return (byte & 0xC0) == 0x80; }

}  // namespace

Utf8Char decode_utf8_at(std::string_view utf8, std::size_t i) {
    const auto lead = static_cast<unsigned char>(utf8[i]);
    std::size_t length = 0;  // bytes in the sequence
    char32_t value = 0;
    char32_t minimum = 0;    // smallest value this length may encode: smaller is overlong
    if (lead < 0x80) {
        return {lead, 1, true};
    } else if ((lead & 0xE0) == 0xC0) {
        length = 2, value = lead & 0x1F, minimum = 0x80;
    } else if ((lead & 0xF0) == 0xE0) {
        length = 3, value = lead & 0x0F, minimum = 0x800;
    } else if ((lead & 0xF8) == 0xF0) {
        length = 4, value = lead & 0x07, minimum = 0x10000;
    } else {  // a continuation byte with no lead, or 0xF8..0xFF
        return {replacement_character, 1, false};
    }
    std::size_t taken = 1;
    while (taken < length && i + taken < utf8.size() && is_continuation(static_cast<unsigned char>(utf8[i + taken]))) {
        value = (value << 6) | (static_cast<unsigned char>(utf8[i + taken]) & 0x3F);
        ++taken;
    }
    const bool surrogate = value >= 0xD800 && value <= 0xDFFF;
    if (taken == length && value >= minimum && !surrogate && value <= 0x10FFFF) return {value, length, true};
    // A truncated sequence ends at the first byte that is not a
    // continuation: that byte starts the next character.
    return {replacement_character, taken, false};
}

std::u32string decode_utf8(std::string_view utf8) {
    std::u32string out;
    out.reserve(utf8.size());
    for (std::size_t i = 0; i < utf8.size();) {
        const Utf8Char c = decode_utf8_at(utf8, i);
        out.push_back(c.code);
        i += c.length;
    }
    return out;
}

std::string encode_utf8(char32_t c) {
    std::string out;
    if (c < 0x80) {
        out += static_cast<char>(c);
    } else if (c < 0x800) {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        out += static_cast<char>(0xE0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (c >> 18));
        out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
    return out;
}

}  // namespace base
