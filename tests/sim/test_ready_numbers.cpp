// figgen's formula engine against GollyGang/Ready's own numbers: from the
// same start (start.vti, written by figgen), 100 steps of figgen equal what
// Ready's command-line tool rdy computed (ready100.vti) on nine cases: the
// five Ready patterns of the catalog (a 1-D and a 3-D one among them), the
// bilaplacian at high accuracy, Sobel stencils, x_pos/y_pos with clamped
// edges at low accuracy, and a rule in double. tests/sim/ready/commands.txt holds the commands that
// made them (tests/sim/ready/make_fixtures.sh).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "ready/pattern.hpp"
#include "figgen_run.hpp"

namespace fs = std::filesystem;

TEST_CASE("100 steps of figgen equal Ready's from the same start", "[formula][ready]") {
    const fs::path cases = fs::path(FIGGEN_SOURCE_DIR) / "tests/sim/ready";
    // Float32 rules differ from Ready by rounding alone (pocl contracts
    // a * b + c into fused multiply-adds, figgen does not): within 1e-4 of
    // the field's own size; a double rule, within 1e-12.
    struct Case {
        const char* name;
        double tolerance;
        int width, height, depth;
    };
    const Case cases_[] = {{"brusselator", 1e-4, 64, 32, 1},  {"cgl-spirals", 1e-4, 64, 32, 1},
                           {"fhn-labyrinth", 1e-4, 64, 32, 1}, {"gs-map-low", 1e-4, 64, 32, 1},
                           {"ks-high", 1e-4, 64, 32, 1},       {"sobel-waves", 1e-4, 64, 32, 1},
                           {"splats-double", 1e-12, 64, 32, 1}, {"tunnelling-1d", 1e-4, 128, 1, 1},
                           {"glider-3d", 1e-4, 16, 16, 16}};
    for (const auto& [name, tolerance, width, height, depth] : cases_) {
        INFO(name);
        const fs::path out = testkit::fresh_dir(std::string("ready-") + name);
        const auto run = testkit::figgen("render " + (cases / name / "start.vti").string() +
                                         " --set steps=100 --set id=figgen --format vti --out " + out.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        const auto ours = ready::read_pattern(out / "figgen.vti", {std::nullopt, true});
        const auto theirs = ready::read_pattern(cases / name / "ready100.vti", {std::nullopt, true});
        REQUIRE(ours.start);
        REQUIRE(theirs.start);
        REQUIRE(ours.start->chemicals.size() == theirs.start->chemicals.size());
        CHECK(ours.start->width == width);
        CHECK(ours.start->height == height);
        CHECK(ours.start->depth == depth);
        double largest = 0, worst = 0;
        for (std::size_t c = 0; c < theirs.start->chemicals.size(); ++c)
            for (std::size_t i = 0; i < theirs.start->chemicals[c].size(); ++i) {
                largest = std::max(largest, std::fabs(theirs.start->chemicals[c][i]));
                worst = std::max(worst, std::fabs(ours.start->chemicals[c][i] - theirs.start->chemicals[c][i]));
            }
        INFO("largest |value| " << largest << ", largest difference " << worst);
        CHECK(largest > 0.01);  // the fields hold something
        CHECK(worst <= tolerance * std::max(1.0, largest));
        // And they moved: 100 steps changed the start.
        const auto start = ready::read_pattern(cases / name / "start.vti", {std::nullopt, true});
        double moved = 0;
        for (std::size_t c = 0; c < theirs.start->chemicals.size(); ++c)
            for (std::size_t i = 0; i < theirs.start->chemicals[c].size(); ++i)
                moved = std::max(moved, std::fabs(start.start->chemicals[c][i] - theirs.start->chemicals[c][i]));
        CHECK(moved > 100 * worst);
    }
}
