// The TOML writer (description/toml_writer.cpp): whatever a table holds,
// its text reads back as the same table, in the order a person reads.
#include <catch2/catch.hpp>

#include <sstream>

#include "description/toml_writer.hpp"

namespace {

std::string written(const toml::table& root) {
    std::ostringstream text;
    description::write_toml(text, root, {"id", "title"}, {{"params", {"formula"}}, {"style", {}}});
    return text.str();
}

}  // namespace

TEST_CASE("any key and string read back as written, quotes and line breaks too", "[description][toml]") {
    const char* const texts[] = {"", "\n", "\r\n", "\nx", "a\nb\n", "'''", "\"\"\"", "x'''y\"\"\"z\n", "a\\b\\",
                                 "tab\there", "\"", "'", "ends with a quote\"", "日本語", "r = 0.5\nready_edges = false\n#",
                                 "\x7f\x01"};
    toml::table params;
    int i = 0;
    for (const char* text : texts) {
        params.insert("k" + std::to_string(i++), text);
        params.insert(text, i);  // as a key too
    }
    const toml::table root{{"id", "x"}, {"title", "a \"title\"\n"}, {"params", params},
                           {"style", toml::table{{"v", toml::array{0.1, -0.0, 1e300, 3}}}}};
    const std::string text = written(root);
    INFO(text);
    toml::table again;
    REQUIRE_NOTHROW(again = toml::parse(text));
    CHECK(again == root);
    // The keys a person reads first come first; a float stays a float.
    CHECK(text.rfind("id = \"x\"\ntitle = ", 0) == 0);
    CHECK_THAT(text, Catch::Contains("v = [0.1, -0.0, 1e+300, 3]"));
    CHECK_THAT(text, Catch::Contains("\"r = 0.5\\nready_edges = false\\n#\" = "));
    CHECK(description::toml_key("plain_key-1") == "plain_key-1");
    CHECK(description::toml_key("a b") == "\"a b\"");
}
