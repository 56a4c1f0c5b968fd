#include "render/line_break.hpp"

#include <mutex>

#include <linebreak.h>

namespace render {

char32_t line_break_stand_in(char32_t c) {
    if (c >= 0x1F1E6 && c <= 0x1F1FF) return U'A';  // a regional indicator: no break inside a flag
    const bool noncharacter = (c >= 0xFDD0 && c <= 0xFDEF) || (c & 0xFFFE) == 0xFFFE;
    const bool not_a_character = (c >= 0xD800 && c <= 0xDFFF) || c > 0x10FFFF;
    if (noncharacter || not_a_character) return U'\uFFFD';
    return c;
}

std::vector<LineBreak> line_breaks(std::u32string_view text, std::string_view language) {
    static std::once_flag started;
    std::call_once(started, init_linebreak);
    std::vector<utf32_t> safe(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) safe[i] = line_break_stand_in(text[i]);
    std::vector<char> breaks(text.size());
    const std::string tag(language);
    set_linebreaks_utf32(safe.data(), safe.size(), tag.empty() ? nullptr : tag.c_str(), breaks.data());
    std::vector<LineBreak> out(text.size());
    for (std::size_t i = 0; i < text.size(); ++i)
        out[i] = breaks[i] == LINEBREAK_MUSTBREAK  ? LineBreak::must
                 : breaks[i] == LINEBREAK_ALLOWBREAK ? LineBreak::allow
                                                     : LineBreak::none;
    return out;
}

}  // namespace render
