// The README stays true: its grid shows every figure of the catalog, and
// the description it teaches with renders.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "figgen_run.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path project = fs::path(FIGGEN_TEST_GOLDEN_DIR).parent_path().parent_path();

std::string readme() {
    std::ifstream in(project / "README.md");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

TEST_CASE("the README's grid shows a committed thumbnail of every catalog figure, moving where it has a film", "[readme]") {
    const std::string text = readme();
    int shown = 0, moving = 0;
    for (const auto& file : description::catalog_files()) {
        const std::string id = file.stem().string();
        INFO(id);
        const bool film = description::load_description(file, {}).animation.has_value();
        // A figure with a film shows its preview's animated thumbnail.
        const std::string name = id + (film ? ".webp" : ".png");
        CHECK_THAT(text, Catch::Contains("](docs/thumbs/" + name + ")](figures/" + id + ".toml)"));
        const fs::path thumb = project / "docs" / "thumbs" / name;
        REQUIRE(fs::exists(thumb));
        if (film) {
            const render::PreviewInfo preview = render::probe_preview(thumb);
            CHECK(preview.width <= 240);
            CHECK(preview.height <= 180);
            CHECK(preview.frames > 1);
            CHECK(preview.loop_count == 0);
            ++moving;
        } else {
            const auto png = render::read_png(thumb).image;
            CHECK(png.width <= 240);
            CHECK(png.height <= 180);
        }
        ++shown;
    }
    // Counted again from the files themselves, with toml++: the grid misses none.
    int files = 0, films = 0;
    for (const auto& entry : fs::directory_iterator(project / "figures")) {
        if (entry.path().extension() != ".toml") continue;
        ++files;
        films += toml::parse_file(entry.path().string()).contains("animation");
    }
    CHECK(files > 30);
    CHECK(shown == files);
    CHECK(moving == films);
}

TEST_CASE("the README's example description renders", "[readme][cli]") {
    const std::string text = readme();
    const auto section = text.find("### Writing a description");
    REQUIRE(section != std::string::npos);
    const auto begin = text.find("```toml\n", section);
    REQUIRE(begin != std::string::npos);
    const auto end = text.find("```", begin + 8);
    const fs::path dir = testkit::fresh_dir("readme-example");
    std::ofstream(dir / "spots.toml") << text.substr(begin + 8, end - begin - 8);
    const testkit::Run run = testkit::figgen("render " + (dir / "spots.toml").string() +
                                             " --format png --scale 0.3 --out " + (dir / "out").string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK(fs::exists(dir / "out" / "spots.png"));
    CHECK(fs::exists(dir / "out" / "spots.json"));
}

namespace {

// The targets `target` (a "dir/CMakeFiles/name.dir") depends on, directly
// or not, as CMake's generated build/CMakeFiles/Makefile2 lists them.
std::set<std::string> dependencies(const std::string& makefile2, const std::string& target) {
    std::map<std::string, std::vector<std::string>> direct;
    std::istringstream lines(makefile2);
    for (std::string line; std::getline(lines, line);) {
        const auto colon = line.find("/all: ");
        if (colon == std::string::npos || line.find(' ') < colon) continue;
        std::string to = line.substr(colon + 6);
        if (to.size() > 4 && to.compare(to.size() - 4, 4, "/all") == 0)
            direct[line.substr(0, colon)].push_back(to.substr(0, to.size() - 4));
    }
    std::set<std::string> all;
    std::vector<std::string> next = {target};
    while (!next.empty()) {
        const std::string t = next.back();
        next.pop_back();
        for (const std::string& d : direct[t])
            if (all.insert(d).second) next.push_back(d);
    }
    return all;
}

}  // namespace

TEST_CASE("make figures builds the program and its modules, not the tests", "[readme]") {
    // The Makefile's rule runs only CMake's figures target...
    const std::string makefile = testkit::slurp(std::filesystem::path(FIGGEN_SOURCE_DIR) / "Makefile");
    const auto rule = makefile.find("\nfigures:");
    REQUIRE(rule != std::string::npos);
    const std::string head = makefile.substr(rule + 1, makefile.find('\n', rule + 1) - rule - 1);
    INFO(head);
    CHECK(head.find(" build") == std::string::npos);  // not `make build` (everything) first
    const std::string recipe = makefile.substr(rule + 1, makefile.find("\n\n", rule + 1) - rule - 1);
    CHECK(recipe.find("--target figures") != std::string::npos);
    // ...which depends on figgen and the modules it opens, and on no test or benchmark.
    const std::string makefile2 = testkit::slurp(std::filesystem::path(FIGGEN_BUILD_DIR) / "CMakeFiles" / "Makefile2");
    if (makefile2.empty()) {
        WARN("no CMakeFiles/Makefile2: this build tree is not CMake's Unix Makefiles");
        return;
    }
    const std::set<std::string> needs = dependencies(makefile2, "figures/CMakeFiles/figures.dir");
    std::string listed;
    for (const std::string& n : needs) listed += n + " ";
    INFO("figures depends on: " << listed);
    CHECK(needs.count("app/CMakeFiles/figgen.dir") == 1);
    CHECK(needs.count("render/CMakeFiles/figgen_media.dir") == 1);
    CHECK(needs.count("render/CMakeFiles/figgen_vector.dir") == 1);
    for (const std::string& n : needs) {
        CHECK(n.rfind("tests/", 0) != 0);
        CHECK(n.rfind("bench/", 0) != 0);
    }
}
