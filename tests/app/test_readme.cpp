// The README stays true: its grid shows every figure of the catalog, and
// the description it teaches with renders.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "figgen_run.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "render/png_io.hpp"
#include "render/video.hpp"

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
    CHECK(shown == 29);
    CHECK(moving == 14);
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
