// The formula atlas (scenes/formula_atlas.cpp): each tile is the formula
// scene's run with the tile's parameters, bit for bit; a tile that goes
// unstable is drawn grey and named; mistakes are refused before any run.
// (Threads, MPI ranks, shards and merges: tests/app/test_cluster.cpp.)
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"

namespace fs = std::filesystem;

namespace {

// A one-chemical rule (Fisher-KPP with decay), r and s swept.
const std::string atlas = R"(
id = "atlas"
title = "an atlas"
scene = "formula_atlas"
seed = 4
[params]
chemicals = 1
width = 16
height = 12
steps = 40
formula = "delta_a = D * laplacian_a + r * a * (1.0f - a) - s * a;"
timestep = 0.2
D = 0.5
x_parameter = "r"
x_range = [0.5, 2.0]
y_parameter = "s"
y_range = [0.0, 0.3]
tiles = [3, 2]
initial = [{chemical = "a", fill = "white_noise", low = 0.0, high = 0.2, shapes = [{shape = "everywhere"}]}]
[style]
show = "a"
[figure]
size = [400, 400]
)";

// The same rule as a formula figure with r and s set.
std::string single(double r, double s) {
    std::string text = atlas;
    const auto cut = [&](const std::string& from, const std::string& to) {
        const std::size_t a = text.find(from), b = text.find(to, a);
        text.erase(a, b - a);
    };
    cut("x_parameter", "initial");
    text.replace(text.find("formula_atlas"), 13, "formula");
    text.replace(text.find("[style]"), 7, "r = " + std::to_string(r) + "\ns = " + std::to_string(s) + "\n[style]");
    text.replace(text.find("show = \"a\""), 10, "show = [\"a\"]");
    text.replace(text.find("[figure]"), 8, "[figure]\npanels = [40]");
    return text;
}

testkit::Run render(const fs::path& dir, const std::string& text, const std::string& id, const std::string& extra = "") {
    testkit::spill(dir / (id + ".toml"), text);
    return testkit::figgen("render " + (dir / (id + ".toml")).string() + " --set id=" + id + " --format png --out " +
                           dir.string() + " " + extra);
}

}  // namespace

TEST_CASE("each tile of a formula atlas is the formula scene's run with its parameters", "[formula][scenes]") {
    const fs::path dir = testkit::fresh_dir("formula-atlas");
    const auto run = render(dir, atlas, "atlas", "--threads 2");
    INFO(run.output);
    REQUIRE(run.status == 0);
    const auto meta = nlohmann::json::parse(testkit::slurp(dir / "atlas.json"));
    REQUIRE(meta["tiles"].size() == 6);
    CHECK(meta["tiles_unstable"] == 0);
    // Tile centres: r at 0.75, 1.25, 1.75; s at 0.225 (top row), 0.075.
    const double rs[] = {0.75, 1.25, 1.75}, ss[] = {0.225, 0.075};
    for (int t = 0; t < 6; ++t) {
        const auto& tile = meta["tiles"][t];
        INFO("tile " << t);
        CHECK(tile["r"].get<double>() == Approx(rs[t % 3]));
        CHECK(tile["s"].get<double>() == Approx(ss[t / 3]));
        const auto one = render(dir, single(tile["r"], tile["s"]), "single-" + std::to_string(t));
        INFO(one.output);
        REQUIRE(one.status == 0);
        const auto m = nlohmann::json::parse(testkit::slurp(dir / ("single-" + std::to_string(t) + ".json")));
        CHECK(m["panels"][0]["state_sha256"] == tile["state_sha256"]);
    }
    // Faster growth (larger r, less decay s) leaves more: the map is the right way round.
    CHECK(meta["tiles"][5]["mean"].get<double>() > meta["tiles"][3]["mean"].get<double>());
    CHECK(meta["tiles"][3]["mean"].get<double>() > meta["tiles"][0]["mean"].get<double>());
}

TEST_CASE("a 1-D atlas tiles space-time diagrams and a 3-D one centre planes of the formula scene's runs",
          "[formula][scenes]") {
    const fs::path dir = testkit::fresh_dir("formula-atlas-dimensions");
    for (const std::string grid : {"width = 24\nheight = 1", "width = 8\nheight = 6\ndepth = 5"}) {
        const bool line = grid.find("depth") == std::string::npos;
        INFO(grid);
        const auto sized = [&](std::string text) {
            text.replace(text.find("width = 16\nheight = 12"), 22, grid);
            return text;
        };
        const std::string id = line ? "line" : "cube";
        const auto run = render(dir, sized(atlas), id, "--threads 2");
        INFO(run.output);
        REQUIRE(run.status == 0);
        const auto meta = nlohmann::json::parse(testkit::slurp(dir / (id + ".json")));
        REQUIRE(meta["tiles"].size() == 6);
        CHECK(meta["tiles_unstable"] == 0);
        if (line) {
            // 40 steps, every step a row, and step 0's.
            CHECK(meta["tile_shows"]["view"] == "space-time diagram");
            CHECK(meta["tile_shows"]["rows"] == 41);
            CHECK(meta["tile_shows"]["stride"] == 1);
        } else {
            CHECK(meta["tile_shows"]["view"] == "plane");
            CHECK(meta["tile_shows"]["z"] == 2);
        }
        // Each tile's last state is the formula figure's with its parameters: two tiles, diagonal.
        for (const int t : {0, 5}) {
            const auto& tile = meta["tiles"][t];
            const std::string one_id = id + "-single-" + std::to_string(t);
            const auto one = render(dir, sized(single(tile["r"], tile["s"])), one_id);
            INFO(one.output);
            REQUIRE(one.status == 0);
            const auto m = nlohmann::json::parse(testkit::slurp(dir / (one_id + ".json")));
            CHECK(m["panels"][0]["state_sha256"] == tile["state_sha256"]);
        }
        CHECK(meta["tiles"][5]["mean"].get<double>() > meta["tiles"][0]["mean"].get<double>());
    }
}

TEST_CASE("a tile that goes unstable is drawn grey and named, the others drawn", "[formula][scenes]") {
    const fs::path dir = testkit::fresh_dir("formula-atlas-unstable");
    std::string text = atlas;
    // Each step multiplies a by about 1 + 4 r^2: at r = 1.75, 13.25^40 = 8e44 leaves float's range; at r = 0.75 it stays.
    text.replace(text.find("r * a * (1.0f - a) - s * a"), 26, "r * r * a * 20.0f - s * a ");
    const auto run = render(dir, text, "unstable");
    INFO(run.output);
    REQUIRE(run.status == 0);
    const auto meta = nlohmann::json::parse(testkit::slurp(dir / "unstable.json"));
    const int unstable = meta["tiles_unstable"];
    CHECK(unstable > 0);
    CHECK(unstable < 6);
    int named = 0;
    for (const auto& tile : meta["tiles"])
        if (tile.contains("unstable")) {
            ++named;
            CHECK_THAT(tile["unstable"].get<std::string>(), Catch::Contains("step"));
        }
    CHECK(named == unstable);
    CHECK(fs::exists(dir / "unstable.png"));
}

TEST_CASE("a formula atlas's mistakes are refused before anything runs", "[formula][scenes]") {
    const fs::path dir = testkit::fresh_dir("formula-atlas-refused");
    testkit::spill(dir / "atlas.toml", atlas);
    const auto refused = [&](const std::string& set) {
        const auto run = testkit::figgen("render " + (dir / "atlas.toml").string() + " --set '" + set + "' --out " +
                                         (dir / "out").string());
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK_FALSE(fs::exists(dir / "out" / "atlas.png"));
        return run.output;
    };
    // q swept, r given: the formula runs, but does not use q.
    CHECK_THAT(refused("x_parameter=q' --set 'r=1.0"),
               Catch::Contains("x_parameter = 'q' is not allowed: the name of a parameter"));
    // q swept, r not given: the formula's own refusal names r.
    CHECK_THAT(refused("x_parameter=q"), Catch::Contains("'r' is not a chemical, parameter, keyword or variable"));
    CHECK_THAT(refused("x_parameter=timestep"), Catch::Contains("(not timestep or dx)"));
    CHECK_THAT(refused("y_parameter=r"), Catch::Contains("a parameter other than x_parameter"));
    CHECK_THAT(refused("x_range=[2, 1]"), Catch::Contains("the second greater"));
    CHECK_THAT(refused("tiles=[0, 2]"), Catch::Contains("each an integer from 1 to 64"));
    CHECK_THAT(refused("r=1.0"), Catch::Contains("the atlas sweeps r over its range"));
    CHECK_THAT(refused("style.show=b"), Catch::Contains("a chemical of the rule: a"));
    CHECK_THAT(refused("style.tile_range=some"), Catch::Contains("\"all\" or \"each\""));
}
