// Strings of a description are text: valid UTF-8 characters, refused with
// the key, the value as a terminal may show it, and what is allowed when
// they are not (description::is_text, Settings::text).
#include <catch2/catch.hpp>

#include <string>

#include "description/description.hpp"
#include "description/plain_name.hpp"

namespace {

const char* const small = "id = \"t\"\nscene = \"diffusion\"\n[figure]\npanels = [0]\n";

// The message parse_description refuses `overrides` with, or "" when it takes them.
std::string refusal(const std::vector<std::string>& overrides, const std::string& text = small) {
    try {
        (void)description::parse_description(text, "t.toml", overrides);
    } catch (const description::UsageError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("is_text takes characters and refuses bytes that are none, controls and noncharacters", "[description]") {
    using description::is_text;
    CHECK(is_text(""));
    CHECK(is_text("Gray-Scott, f = 0.035"));
    CHECK(is_text("雪花 \xF0\x9F\x87\xBA\xF0\x9F\x87\xB8 flag, tab\there, two\nlines\r\n"));  // CJK, U+1F1FA U+1F1F8
    CHECK(is_text("\xEF\xBF\xBD"));                 // U+FFFD, a character
    CHECK(is_text("\xF3\xA0\x80\x81"));             // U+E0001, a tag
    CHECK_FALSE(is_text("\xFF"));                   // never in UTF-8
    CHECK_FALSE(is_text("caf\xC3"));                // truncated
    CHECK_FALSE(is_text("\xC0\xAF"));               // overlong '/'
    CHECK_FALSE(is_text("\xED\xA0\x80"));           // the surrogate U+D800
    CHECK_FALSE(is_text("\xF4\x90\x80\x80"));       // U+110000
    CHECK_FALSE(is_text("\xEF\xBF\xBF"));           // U+FFFF
    CHECK_FALSE(is_text("\xEF\xBF\xBE"));           // U+FFFE
    CHECK_FALSE(is_text("\xEF\xB7\x90"));           // U+FDD0
    CHECK_FALSE(is_text("\xF4\x8F\xBF\xBF"));       // U+10FFFF
    CHECK_FALSE(is_text(std::string("a\0b", 3)));   // NUL
    CHECK_FALSE(is_text("a\x1B[2Jb"));              // ESC
    CHECK_FALSE(is_text("a\xC2\x85"));              // U+0085, a C1 control
    CHECK(is_text("\xEF\xB7\x8F\xEF\xB7\xB0"));     // U+FDCF and U+FDF0, beside the noncharacters
}

TEST_CASE("printable_short escapes noncharacters and cuts long values on a character", "[description]") {
    CHECK(description::printable("a\xEF\xBF\xBF") == "a\\uFFFF");
    CHECK(description::printable("\xF4\x8F\xBF\xBF") == "\\U0010FFFF");
    CHECK(description::printable_short("short") == "short");
    CHECK(description::printable_short(std::string(100, 'x')) == std::string(57, 'x') + "...");
    // 20 three-byte ideographs: 57 bytes hold 19 of them whole.
    std::string ideographs;
    for (int i = 0; i < 30; ++i) ideographs += "\xE9\x9B\xAA";  // 雪
    std::string nineteen;
    for (int i = 0; i < 19; ++i) nineteen += "\xE9\x9B\xAA";
    CHECK(description::printable_short(ideographs) == nineteen + "...");
    // An escape is never cut: 54 letters, then \xFF (4 bytes) would end at 58.
    CHECK(description::printable_short(std::string(54, 'a') + "\xFF" + std::string(20, 'b')) == std::string(54, 'a') + "...");
}

TEST_CASE("a string that is not text is refused with its key before anything runs", "[description]") {
    // --set title takes any bytes as its text: invalid UTF-8 reached cairo before.
    const std::string bad_title = refusal({"title=caf\xC3"});
    CHECK(bad_title == "--set title=caf\\xC3: title = \"caf\\xC3\" is not allowed: " + std::string(description::text_allowed));
    const std::string nonchar = refusal({"title=a\xEF\xBF\xBF"});
    CHECK(nonchar.find("title = \"a\\uFFFF\" is not allowed: text of valid UTF-8") != std::string::npos);
    // A [figure] key given by --set, a panel title with ESC.
    const std::string panel = refusal({"figure.panel_title=step \x1B[2J{step}"});
    CHECK(panel.find("figure.panel_title = \"step \\x1B[2J{step}\" is not allowed: text of valid UTF-8") !=
          std::string::npos);
    // In the file: original_caption with U+FFFF, at its line.
    const std::string in_file =
        refusal({}, std::string(small).insert(0, "original_caption = \"snow \\uFFFF\"\n"));
    CHECK(in_file.rfind("t.toml:1: original_caption = \"snow \\uFFFF\" is not allowed", 0) == 0);
    // A long value is shown short, on one line.
    const std::string long_value = refusal({"title=" + std::string(100000, 'a') + "\x01"});
    CHECK(long_value.find("title = \"" + std::string(57, 'a') + "...\" is not allowed") != std::string::npos);
    CHECK(long_value.size() < 400);  // the --set it came from is shown short too
    // Characters are taken, flags and CJK among them.
    CHECK(refusal({"title=\xF0\x9F\x87\xBA\xF0\x9F\x87\xB8 雪花"}).empty());
}
