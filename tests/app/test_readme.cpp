// The README stays true: its grid shows every figure of the catalog, and
// the description it teaches with renders.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "figgen_run.hpp"
#include "description/catalog.hpp"
#include "render/png_io.hpp"

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

TEST_CASE("the README's grid shows a committed thumbnail of every catalog figure", "[readme]") {
    const std::string text = readme();
    int shown = 0;
    for (const auto& file : description::catalog_files()) {
        const std::string id = file.stem().string();
        INFO(id);
        CHECK_THAT(text, Catch::Contains("](docs/thumbs/" + id + ".png)](figures/" + id + ".toml)"));
        const fs::path thumb = project / "docs" / "thumbs" / (id + ".png");
        REQUIRE(fs::exists(thumb));
        const auto png = render::read_png(thumb).image;
        CHECK(png.width <= 240);
        CHECK(png.height <= 180);
        ++shown;
    }
    CHECK(shown == 29);
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
