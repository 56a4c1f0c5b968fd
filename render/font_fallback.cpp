#include "render/font_fallback.hpp"

#include <mutex>
#include <stdexcept>

#include <fontconfig/fontconfig.h>

namespace render {
namespace {

std::mutex& fontconfig_mutex() {
    static std::mutex m;
    return m;
}

// The process's configuration, loaded on first use and kept: loading it
// reads the configuration files and the font caches.
FcConfig* configuration() {
    static FcConfig* config = [] {
        FcConfig* c = FcInitLoadConfigAndFonts();
        if (!c) throw std::runtime_error("fontconfig cannot load its configuration, so no fallback font can be found");
        return c;
    }();
    return config;
}

template <class T, void (*destroy)(T*)>
struct Owned {
    T* p;
    explicit Owned(T* pointer) : p(pointer) {
        if (!p) throw std::bad_alloc();
    }
    ~Owned() { destroy(p); }
    Owned(const Owned&) = delete;
    Owned& operator=(const Owned&) = delete;
};

}  // namespace

std::optional<FontFile> fallback_font(char32_t c, std::string_view language) {
    const std::lock_guard lock(fontconfig_mutex());
    FcConfig* config = configuration();
    Owned<FcPattern, FcPatternDestroy> pattern(FcPatternCreate());
    FcPatternAddString(pattern.p, FC_FAMILY, reinterpret_cast<const FcChar8*>("sans-serif"));
    {
        Owned<FcCharSet, FcCharSetDestroy> wanted(FcCharSetCreate());
        FcCharSetAddChar(wanted.p, c);
        FcPatternAddCharSet(pattern.p, FC_CHARSET, wanted.p);
    }
    if (!language.empty()) {
        const std::string tag(language);
        Owned<FcLangSet, FcLangSetDestroy> languages(FcLangSetCreate());
        FcLangSetAdd(languages.p, reinterpret_cast<const FcChar8*>(tag.c_str()));
        FcPatternAddLangSet(pattern.p, FC_LANG, languages.p);
    }
    FcPatternAddBool(pattern.p, FC_SCALABLE, FcTrue);
    FcConfigSubstitute(config, pattern.p, FcMatchPattern);
    FcDefaultSubstitute(pattern.p);
    FcResult result = FcResultNoMatch;
    FcFontSet* sorted = FcFontSort(config, pattern.p, FcFalse, nullptr, &result);
    if (!sorted) return std::nullopt;
    Owned<FcFontSet, FcFontSetDestroy> fonts(sorted);
    for (int i = 0; i < fonts.p->nfont; ++i) {
        const FcPattern* font = fonts.p->fonts[i];
        FcCharSet* has = nullptr;
        if (FcPatternGetCharSet(font, FC_CHARSET, 0, &has) != FcResultMatch || !FcCharSetHasChar(has, c)) continue;
        FcBool flag = FcFalse;
        if (FcPatternGetBool(font, FC_COLOR, 0, &flag) == FcResultMatch && flag) continue;  // bitmaps in colour
        if (FcPatternGetBool(font, FC_SCALABLE, 0, &flag) == FcResultMatch && !flag) continue;
        FcChar8* file = nullptr;
        int index = 0;
        if (FcPatternGetString(font, FC_FILE, 0, &file) != FcResultMatch) continue;
        if (FcPatternGetInteger(font, FC_INDEX, 0, &index) != FcResultMatch) index = 0;
        return FontFile{reinterpret_cast<const char*>(file), index};
    }
    return std::nullopt;
}

bool known_language(std::string_view language) {
    if (language.empty()) return false;
    const std::lock_guard lock(fontconfig_mutex());
    const std::string tag(language);
    Owned<FcStrSet, FcStrSetDestroy> languages(FcGetLangs());
    return FcStrSetMember(languages.p, reinterpret_cast<const FcChar8*>(tag.c_str())) == FcTrue;
}

}  // namespace render
