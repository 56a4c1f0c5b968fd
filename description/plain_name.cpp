#include "description/plain_name.hpp"

#include <cstdint>
#include <cstdio>

#include "base/utf8.hpp"

namespace description {

bool is_language_tag(std::string_view tag) {
    if (tag.empty()) return true;
    if (tag.size() < 2 || tag.size() > 35) return false;
    std::size_t letters = 0;
    while (letters < tag.size() && tag[letters] >= 'a' && tag[letters] <= 'z') ++letters;
    if (letters < 2 || letters > 3 || (letters < tag.size() && tag[letters] != '-')) return false;
    for (const char c : tag)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
    return tag.back() != '-' && tag.find("--") == std::string_view::npos;
}

bool is_plain_id(std::string_view id) {
    if (id.empty() || id.size() > 100 || id.front() == '.' || id.find("..") != std::string_view::npos) return false;
    for (const char c : id) {
        const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        if (!alnum && c != '-' && c != '_' && c != '.') return false;
    }
    return true;
}

namespace {

// The length of the UTF-8 sequence starting at text[at] and its code point,
// or 0 when it is not valid UTF-8.
std::size_t decode_utf8(std::string_view text, std::size_t at, std::uint32_t& code) {
    const base::Utf8Char c = base::decode_utf8_at(text, at);
    code = c.code;
    return c.valid ? c.length : 0;
}

// The 66 code points Unicode reserves never to be characters.
bool is_noncharacter(std::uint32_t code) { return (code >= 0xFDD0 && code <= 0xFDEF) || (code & 0xFFFE) == 0xFFFE; }

bool is_control(std::uint32_t code) { return code < 0x20 || (code >= 0x7F && code < 0xA0); }

bool is_bidi_control(std::uint32_t code) {
    return (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069) || code == 0x200E ||
           code == 0x200F || code == 0x061C;
}

}  // namespace

std::string printable(std::string_view text, std::size_t most) {
    std::string shown;
    char escape[16];
    for (std::size_t at = 0; at < text.size();) {
        if (shown.size() >= most) {
            shown += "... (" + std::to_string(text.size()) + " bytes in all)";
            break;
        }
        std::uint32_t code = 0;
        const std::size_t length = decode_utf8(text, at, code);
        if (length == 0) {
            std::snprintf(escape, sizeof escape, "\\x%02X", static_cast<unsigned char>(text[at]));
            shown += escape;
            ++at;
            continue;
        }
        if (code == '\n') {
            shown += "\\n";
        } else if (code == '\t') {
            shown += "\\t";
        } else if (code < 0x20 || code == 0x7F || (code >= 0x80 && code < 0xA0)) {
            std::snprintf(escape, sizeof escape, "\\x%02X", static_cast<unsigned>(code));
            shown += escape;
        } else if (is_bidi_control(code) || is_noncharacter(code)) {
            std::snprintf(escape, sizeof escape, code > 0xFFFF ? "\\U%08X" : "\\u%04X", static_cast<unsigned>(code));
            shown += escape;
        } else {
            shown.append(text.substr(at, length));
        }
        at += length;
    }
    return shown;
}

std::string printable_short(std::string_view text, std::size_t most) {
    const std::string shown = printable(text, most + 16);  // never the whole of a long text
    if (shown.size() <= most) return shown;
    // Back to the start of a character: a cut may split a UTF-8 sequence.
    std::size_t cut = most > 3 ? most - 3 : 0;
    while (cut > 0 && (static_cast<unsigned char>(shown[cut]) & 0xC0) == 0x80) --cut;
    // Nor inside an escape (\x1B, \u202E, \U0010FFFF: at most 10 bytes), which
    // would read as another character. A backslash of the text's own may
    // cut a little short: harmless.
    for (std::size_t back = 1; back < 10 && back <= cut; ++back)
        if (shown[cut - back] == '\\') {
            const char kind = shown[cut - back + 1];
            const std::size_t length = kind == 'U' ? 10 : kind == 'u' ? 6 : kind == 'x' ? 4 : 2;
            if (back < length) cut -= back;
            break;
        }
    return shown.substr(0, cut) + "...";
}

bool is_text(std::string_view text) {
    for (std::size_t at = 0; at < text.size();) {
        std::uint32_t code = 0;
        const std::size_t length = decode_utf8(text, at, code);
        if (length == 0 || is_noncharacter(code)) return false;
        if (is_control(code) && code != '\t' && code != '\n' && code != '\r') return false;
        at += length;
    }
    return true;
}

}  // namespace description
