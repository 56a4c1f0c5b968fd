#include "app/render/terminal_text.hpp"

#include <locale.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cwchar>

#include "base/utf8.hpp"

namespace app {
namespace {

// A UTF-8 character type for this thread while it lives: wcwidth reads the
// thread's locale, and the program's own stays "C".
class Utf8Locale {
public:
    Utf8Locale() : locale_(::newlocale(LC_CTYPE_MASK, "C.UTF-8", static_cast<locale_t>(0))) {
        if (locale_) previous_ = ::uselocale(locale_);
    }
    ~Utf8Locale() {
        if (!locale_) return;
        ::uselocale(previous_);
        ::freelocale(locale_);
    }
    Utf8Locale(const Utf8Locale&) = delete;
    Utf8Locale& operator=(const Utf8Locale&) = delete;

private:
    locale_t locale_;
    locale_t previous_ = LC_GLOBAL_LOCALE;
};

int columns_of(char32_t c) {
    const int w = ::wcwidth(static_cast<wchar_t>(c));
    return w < 0 ? 1 : w;
}

}  // namespace

int display_width(std::string_view utf8) {
    const Utf8Locale locale;
    int columns = 0;
    for (const char32_t c : base::decode_utf8(utf8)) columns += columns_of(c);
    return columns;
}

std::string fit_columns(std::string_view utf8, int columns) {
    if (display_width(utf8) <= columns) return std::string(utf8);
    const Utf8Locale locale;
    std::string out;
    int used = 0;
    const int room = columns - 3;  // for "..."
    for (std::size_t at = 0; at < utf8.size();) {
        const base::Utf8Char c = base::decode_utf8_at(utf8, at);
        const std::size_t bytes = c.valid ? c.length : 1;  // a malformed byte, one column
        const int w = c.valid ? columns_of(c.code) : 1;
        if (used + w > room) break;
        out.append(utf8.substr(at, bytes));
        used += w;
        at += bytes;
    }
    return out + "...";
}

std::string pad_columns(std::string_view utf8, int columns) {
    std::string out(utf8);
    const int width = display_width(utf8);
    if (width < columns) out.append(static_cast<std::size_t>(columns - width), ' ');
    return out;
}

int terminal_columns(int fd) {
    winsize size{};
    if (::ioctl(fd, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
    if (const char* env = std::getenv("COLUMNS")) {
        char* end = nullptr;
        const long n = std::strtol(env, &end, 10);
        if (end != env && *end == '\0' && n > 0 && n < 10000) return static_cast<int>(n);
    }
    return 80;
}

}  // namespace app
