#pragma once
// Fallback faces through fontconfig: for a character the figure's own font
// (DejaVu Sans) lacks, the installed face that has it, chosen by the
// system's font configuration as any desktop program would (Noto Sans CJK
// for Chinese and Japanese, where deps.sh installs fonts-noto-cjk).
// fontconfig is started only when such a character is first drawn, so that
// a figure in Latin, Greek or Cyrillic never reads the font configuration.

#include <optional>
#include <string>
#include <string_view>

namespace render {

struct FontFile {
    std::string path;  // the font file
    int index = 0;     // the face within it (a .ttc collection holds several)
    bool operator<(const FontFile& o) const { return path != o.path ? path < o.path : index < o.index; }
    bool operator==(const FontFile& o) const = default;
};

// The scalable, non-colour face fontconfig ranks first for sans-serif text
// in `language` (an RFC 3066 tag such as "zh-cn" or "ja"; empty: the
// configuration's default) among those that have `c`; none when no
// installed font has it.
std::optional<FontFile> fallback_font(char32_t c, std::string_view language);

// Whether fontconfig knows `language` as a language tag ("zh-cn", "ja", "en").
bool known_language(std::string_view language);

}  // namespace render
