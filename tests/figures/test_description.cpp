#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "figures/catalog.hpp"
#include "figures/description.hpp"
#include "figures/field_stats.hpp"
#include "figures/scene.hpp"

namespace fs = std::filesystem;

TEST_CASE("every catalog description loads and names a known scene after its own file", "[description]") {
    const auto files = figures::catalog_files();
    REQUIRE_FALSE(files.empty());
    for (const auto& file : files) {
        INFO(file.string());
        const figures::Description d = figures::load_description(file);
        CHECK(d.id == file.stem().string());  // `make figures` names outputs by file, figgen by id
        CHECK_FALSE(d.title.empty());
        CHECK_FALSE(d.source.empty());
        const auto& scenes = figures::scenes();
        CHECK(std::any_of(scenes.begin(), scenes.end(), [&](const auto& s) { return s.model == d.model; }));
    }
}

TEST_CASE("overrides reach the right section with TOML types", "[description]") {
    const auto file = figures::resolve_figure("tc7-1");
    const figures::Description d = figures::load_description(
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
    CHECK_THROWS_WITH(figures::load_description(file, {"noequals"}), Catch::Contains("expected key=value"));
    CHECK_THROWS_WITH(figures::load_description(file, {"colour.x=1"}), Catch::Contains("unknown section 'colour'"));
}

TEST_CASE("format_step writes the true step into a title", "[description]") {
    CHECK(figures::format_step("step {step}", 15) == "step 15");
    CHECK(figures::format_step("{step} of {step}", 3) == "3 of 3");
    CHECK(figures::format_step("no step", 3) == "no step");
}

TEST_CASE("a field with a non-finite value stops the figure with an error", "[description]") {
    sim::Grid<double> field(3, 3, 0.5);
    CHECK_NOTHROW(figures::require_finite(field, "diffusion", 4));
    field(1, 2) = std::nan("");
    CHECK_THROWS_WITH(figures::require_finite(field, "gray_scott", 4),
                      "gray_scott went numerically unstable at step 4 (non-finite values); no image written");
    field(1, 2) = INFINITY;
    CHECK_THROWS(figures::require_finite(field, "diffusion", 4));
}

TEST_CASE("field statistics are exact for a known field", "[description]") {
    sim::Grid<double> field(2, 2);
    field(0, 0) = 1;
    field(0, 1) = 2;
    field(1, 0) = 3;
    field(1, 1) = -2;
    const auto stats = figures::field_statistics(field);
    CHECK(stats["min"] == -2.0);
    CHECK(stats["max"] == 3.0);
    CHECK(stats["sum"] == 4.0);
    CHECK(stats["mean"] == 1.0);
    // SHA-256 of the 32 bytes of four little-endian doubles, computed independently:
    // python3 -c "import hashlib,struct; print(hashlib.sha256(struct.pack('<4d',1,2,3,-2)).hexdigest())"
    CHECK(figures::state_hash(field) == "2bac1189f87925bde11530a00007af4b28eea3115bd5cc1a6c0a6e4969380744");
}
