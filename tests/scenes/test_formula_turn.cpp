// A 3-D formula figure's film may end by turning the camera once round the
// last step (animation.turn_frames, scenes/formula.cpp): the frames come
// after the run's, at its last step, each from further round, the same
// bytes on any number of threads; every other figure refuses the key.
// (Films made in segments by MPI ranks: tests/app/test_cluster.cpp.)
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"

namespace fs = std::filesystem;

namespace {

// fx-glider-3d on 16^3 cells for 300 steps: 11 frames of the run, then `turn` turning.
const std::string small_glider =
    "render fx-glider-3d --set width=16 --set height=16 --set depth=16 --set steps=300 --set 'figure.panels=[0,300]' "
    "--set 'animation.steps=[0,300]' --set animation.stride=30 --scale 0.3 ";

}  // namespace

TEST_CASE("a 3-D film turns the camera round its last step after the run, the same bytes on any threads",
          "[formula][scenes][film]") {
    const fs::path dir = testkit::fresh_dir("formula-turn");
    const auto one = testkit::figgen(small_glider + "--set animation.turn_frames=12 --frames --threads 1 --out " +
                                     (dir / "one").string());
    INFO(one.output);
    REQUIRE(one.status == 0);
    const auto meta = nlohmann::json::parse(testkit::slurp(dir / "one" / "fx-glider-3d.json"));
    const auto& film = meta["animation"];
    CHECK(film["frames"] == 23);
    CHECK(film["turn_frames"] == 12);
    for (int f = 10; f < 23; ++f) CHECK(film["steps"][f] == 300);
    CHECK(film["steps"][9] == 270);
    // Each frame of the turn is a view of its own, none the run's last.
    std::set<std::string> seen;
    for (int f = 10; f < 23; ++f) {
        char name[16];
        std::snprintf(name, sizeof name, "%05d.png", f);
        seen.insert(testkit::slurp(dir / "one" / "fx-glider-3d-frames" / name));
    }
    CHECK(seen.size() == 13);
    // Two threads: the same film.
    const auto two = testkit::figgen(small_glider + "--set animation.turn_frames=12 --threads 2 --out " +
                                     (dir / "two").string());
    INFO(two.output);
    REQUIRE(two.status == 0);
    CHECK(testkit::slurp(dir / "two" / "fx-glider-3d.mp4") == testkit::slurp(dir / "one" / "fx-glider-3d.mp4"));
    // Without the key the film is the run's 11 frames, and no turn is said.
    const auto plain = testkit::figgen(small_glider + "--out " + (dir / "plain").string());
    REQUIRE(plain.status == 0);
    const auto plain_meta = nlohmann::json::parse(testkit::slurp(dir / "plain" / "fx-glider-3d.json"));
    CHECK(plain_meta["animation"]["frames"] == 11);
    CHECK_FALSE(plain_meta["animation"].contains("turn_frames"));
}

TEST_CASE("animation.turn_frames is refused where there is no 3-D view to turn", "[formula][scenes][film]") {
    const fs::path dir = testkit::fresh_dir("formula-turn-refused");
    const auto refused = [&](const std::string& args) {
        const auto run = testkit::figgen("render " + args + " --out " + (dir / "out").string());
        INFO(run.output);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK_FALSE(fs::exists(dir / "out"));
        return run.output;
    };
    CHECK_THAT(refused("fx-brusselator --set animation.turn_frames=5"),
               Catch::Contains("animation.turn_frames = 5 is not allowed: 0: a 2-D grid has no 3-D view to turn"));
    CHECK_THAT(refused("fx-tunnelling --set animation.turn_frames=5"),
               Catch::Contains("0: a 1-D grid has no 3-D view to turn"));
    CHECK_THAT(refused("tc7-1 --set animation.turn_frames=5"),
               Catch::Contains("0: the scene diffusion draws no 3-D view to turn"));
    CHECK_THAT(refused("fx-glider-3d --set animation.turn_frames=3601"), Catch::Contains("an integer from 0 to 3600"));
    CHECK_THAT(refused("fx-glider-3d --set animation.turn_frames=-1"), Catch::Contains("an integer from 0 to 3600"));
}
