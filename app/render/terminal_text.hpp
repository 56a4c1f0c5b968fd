#pragma once
// Text for a terminal: widths in columns, as the terminal shows them (an
// ideograph or a fullwidth form takes two columns, a combining mark none),
// by the C library's wcwidth in a UTF-8 locale, so that tables of settings
// stay aligned when a value is Chinese or Japanese.

#include <string>
#include <string_view>

namespace app {

// The columns `utf8` takes; a character the C library cannot place (a
// control character, malformed UTF-8) counts as one.
int display_width(std::string_view utf8);

// `utf8` cut to at most `columns`, whole characters only, ending with "..."
// when it was cut.
std::string fit_columns(std::string_view utf8, int columns);

// `utf8` followed by spaces up to `columns` (unchanged when it is wider).
std::string pad_columns(std::string_view utf8, int columns);

// The width of the terminal on `fd`, in columns: the terminal's own, else
// $COLUMNS, else 80.
int terminal_columns(int fd);

}  // namespace app
