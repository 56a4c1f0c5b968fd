#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "description/catalog.hpp"
#include "description/description.hpp"

namespace fs = std::filesystem;

TEST_CASE("every catalog description loads and is named after its own file", "[description]") {
    const auto files = description::catalog_files();
    REQUIRE_FALSE(files.empty());
    for (const auto& file : files) {
        INFO(file.string());
        const description::Description d = description::load_description(file);
        CHECK(d.id == file.stem().string());  // `make figures` names outputs by file, figgen by id
        CHECK_FALSE(d.title.empty());
        CHECK_FALSE(d.source.empty());
        CHECK_FALSE(d.scene.empty());
    }
}

TEST_CASE("overrides reach the right section with TOML types", "[description]") {
    const auto file = description::resolve_figure("tc7-1");
    const description::Description d = description::load_description(
        file, {"r=0.2", "boundary=wrap", "figure.panels=[1,2]", "animation.stride=3", "style.alpha=0.5"}, 77);
    CHECK(d.params["r"].value<double>() == 0.2);
    CHECK(d.params["boundary"].value<std::string>() == "wrap");  // not TOML: taken as a string
    CHECK(d.panels == std::vector<int>{1, 2});
    REQUIRE(d.animation);
    CHECK(d.animation->stride == 3);
    CHECK(d.animation->frame_count() == 21);  // steps 0, 3, ..., 60
    CHECK(d.style["alpha"].value<double>() == 0.5);
    CHECK(d.seed == 77);
    CHECK(d.last_step(true) == 60);
    CHECK(d.last_step(false) == 2);
    CHECK_THROWS_WITH(description::load_description(file, {"noequals"}), Catch::Contains("expected key=value"));
    CHECK_THROWS_WITH(description::load_description(file, {"colour.x=1"}), Catch::Contains("unknown section 'colour'"));
}

TEST_CASE("format_step writes the true step into a title", "[description]") {
    CHECK(description::format_step("step {step}", 15) == "step 15");
    CHECK(description::format_step("{step} of {step}", 3) == "3 of 3");
    CHECK(description::format_step("no step", 3) == "no step");
}
