#pragma once
// Names that come from a description or the command line and end up in file
// names or in one-line messages.

#include <string>
#include <string_view>

namespace description {

// What a figure id may be, for messages: it names the figure's files inside
// the output folder, so it cannot lead anywhere else.
inline constexpr const char* plain_id_allowed =
    "a plain name of ASCII letters, digits, '-', '_' and '.', not starting with '.', without '..', 1 to 100 "
    "characters";

// Whether `id` is such a name: no path separator, no "..", no control,
// bidirectional or other non-ASCII character, not empty, not hidden.
bool is_plain_id(std::string_view id);

// Whether `tag` may be a language tag: empty (none given), or 2 to 35
// lower-case ASCII letters, digits and hyphens, starting with 2 or 3
// letters ("zh-cn", "ja", "en"): fontconfig's form.
bool is_language_tag(std::string_view tag);

// `text` quoted for a one-line message: control characters, the
// bidirectional controls (U+202A..U+202E, U+2066..U+2069, U+200E, U+200F,
// U+061C), noncharacters and invalid UTF-8 are written as escapes (\n,
// \x00, \u202E, \uFFFF), so a hostile name can neither break the line nor
// reorder what a terminal shows. What is shown stops after about `most`
// bytes, with the text's length, so a 10 MB value never makes a 10 MB message.
inline constexpr std::size_t printable_most = 400;
std::string printable(std::string_view text, std::size_t most = printable_most);
// printable(text), cut to at most `most` bytes (a whole character or escape
// last) and "..." when it was longer: a long value in a one-line message.
std::string printable_short(std::string_view text, std::size_t most = 60);

// What a string of a description may hold, for messages: every string may
// be drawn (titles, captions, labels), and the line breaker and shaper take
// only characters.
inline constexpr const char* text_allowed =
    "text of valid UTF-8 characters, without control characters other than tab and line breaks and without "
    "noncharacters (U+FDD0..U+FDEF, U+FFFE and U+FFFF of each plane)";

// Whether `text` is such a string: valid UTF-8 (no stray or truncated
// bytes, overlong forms, surrogates or values above U+10FFFF) whose code
// points are neither C0 or C1 controls (tab, line feed and carriage return
// allowed) nor noncharacters.
bool is_text(std::string_view text);

}  // namespace description
