// figgen describe: every setting of every figure, with value, default, range and meaning.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "figgen_run.hpp"
#include "description/catalog.hpp"

namespace {

// The line of `key` in the [section] block of describe's output ("" if none).
std::string line_of(const std::string& text, const std::string& section, const std::string& key) {
    const auto begin = text.find("\n[" + section + "]\n");
    if (begin == std::string::npos) return "";
    std::istringstream lines(text.substr(begin + section.size() + 4));
    for (std::string line; std::getline(lines, line) && !line.empty();)
        if (line.rfind("  " + key + " ", 0) == 0) return line;
    return "";
}

}  // namespace

TEST_CASE("figgen describe lists every parameter of every figure with a meaning", "[cli][describe]") {
    int figures = 0, parameters = 0;
    for (const auto& file : description::catalog_files()) {
        const std::string id = file.stem().string();
        INFO(id);
        const testkit::Run run = testkit::figgen("describe " + id);
        REQUIRE(run.status == 0);
        CHECK_THAT(run.output, Catch::StartsWith(id + ": "));
        // Every key the description sets in [params] and [style], read here
        // with toml++ independently, is listed with a meaning (the last column,
        // from character 112 on).
        const toml::table root = toml::parse_file(file.string());
        for (const char* section : {"params", "style"}) {
            const toml::table* table = root[section].as_table();
            if (!table) continue;
            for (const auto& entry : *table) {
                const std::string key(entry.first.str());
                INFO(section << "." << key);
                const std::string line = line_of(run.output, section, key);
                REQUIRE_FALSE(line.empty());
                REQUIRE(line.size() > 112);
                CHECK(line.find_first_not_of(' ', 112) != std::string::npos);
                ++parameters;
            }
        }
        ++figures;
    }
    int files = 0;  // the catalog counted from the folder itself
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(FIGGEN_SOURCE_DIR) / "figures"))
        files += entry.path().extension() == ".toml";
    CHECK(files > 30);
    CHECK(figures == files);
    CHECK(parameters > 100);
}

TEST_CASE("figgen describe gives tc7-1's value, default and checked range", "[cli][describe]") {
    const testkit::Run run = testkit::figgen("describe tc7-1");
    REQUIRE(run.status == 0);
    // r: 0.1 in the description, 0.1 by default (sim::DiffusionParams), checked 0..0.25.
    CHECK_THAT(line_of(run.output, "params", "r"),
               Catch::Matches("  r +0\\.1 +0\\.1 +from 0 to 0\\.25 +diffusion rate per step.*"));
    // n: 9, an integer 1..8192.
    CHECK_THAT(line_of(run.output, "params", "n"), Catch::Matches("  n +9 +9 +an integer from 1 to 8192 +grid size.*"));
    CHECK_THAT(line_of(run.output, "animation", "fps"), Catch::Matches("  fps +10 +.*frames per second.*"));
    const testkit::Run bad = testkit::figgen("describe tc7-99");
    CHECK(bad.status == 2);
    CHECK_THAT(bad.output, Catch::Contains("unknown figure id 'tc7-99'; closest: tc7-9"));
}

namespace {

// Terminal columns of a line, counted here from the code points: two for
// CJK ideographs, kana and fullwidth forms (East Asian Wide), one for the
// rest of what these lines hold.
int columns_of(const std::string& utf8) {
    int columns = 0;
    for (std::size_t i = 0; i < utf8.size();) {
        const auto lead = static_cast<unsigned char>(utf8[i]);
        const int bytes = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
        char32_t c = bytes == 1 ? lead : lead & (0xFF >> (bytes + 1));
        for (int k = 1; k < bytes; ++k) c = (c << 6) | (static_cast<unsigned char>(utf8[i + k]) & 0x3F);
        const bool wide = (c >= 0x2E80 && c <= 0x9FFF) || (c >= 0xFF01 && c <= 0xFF60) || (c >= 0x3000 && c <= 0x303F);
        columns += wide ? 2 : 1;
        i += static_cast<std::size_t>(bytes);
    }
    return columns;
}

// The column at which the n-th (from 0) `needle` starts in `line`.
int column_of(const std::string& line, const std::string& needle, int n = 0) {
    auto at = line.find(needle);
    for (; n > 0 && at != std::string::npos; --n) at = line.find(needle, at + 1);
    return at == std::string::npos ? -1 : columns_of(line.substr(0, at));
}

}  // namespace

TEST_CASE("figgen describe aligns its columns by display width with Chinese values", "[cli][describe]") {
    const auto dir = testkit::fresh_dir("describe-wide");
    const auto file = dir / "wide.toml";
    std::ofstream(file) << "id = \"wide\"\nscene = \"snowflake\"\noriginal_caption = \"图 3 雪花\"\nlanguage = \"zh-cn\"\n"
                           "[params]\nruns = [{rule = \"0101010\", label = \"(a)\"}]\n"
                           "[style]\ncaption = \"图{label} 规则{rule}\"\nice_colour = \"#1d4e89\"\n";
    const testkit::Run run = testkit::figgen("describe " + file.string());
    REQUIRE(run.status == 0);
    CHECK(run.output.find("original caption (zh-cn): 图 3 雪花") != std::string::npos);
    const std::string wide = line_of(run.output, "style", "caption");
    const std::string narrow = line_of(run.output, "style", "ice_colour");
    REQUIRE(!wide.empty());
    REQUIRE(!narrow.empty());
    // The defaults' column starts at the same place on both lines: the
    // Chinese value took its 2 columns a character, not its 3 bytes.
    const int column = column_of(narrow, "\"#1d4e89\"", 1);
    CHECK(column == 2 + 20 + 1 + 28 + 1);
    CHECK(column_of(wide, "\"{label} {rule}\"") == column);
}
