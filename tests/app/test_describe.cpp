// figgen describe: every setting of every figure, with value, default, range and meaning.
#include <catch2/catch.hpp>
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
    CHECK(figures == 29);
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
