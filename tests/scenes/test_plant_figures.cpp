// The pl figures as a user drives them, and the numbers they record.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"

namespace fs = std::filesystem;

namespace {
std::filesystem::path out_dir(const std::string& name) { return testkit::fresh_dir("plants-" + name); }
}  // namespace

using testkit::figgen;
using testkit::render_json;
using testkit::Run;

TEST_CASE("the club moss draws the article's 6 (6^n - 1) / 5 segments", "[plants]") {
    const auto meta = render_json("pl-lsys-lycopodium", "");
    REQUIRE(meta["panels"].size() == 1);
    CHECK(meta["panels"][0]["segments"] == 6 * (216 - 1) / 5);  // depth 3: 258
    CHECK(meta["panels"][0]["reading"] == "article");
}

TEST_CASE("an L-system rule can be given on the command line", "[plants]") {
    // F -> FF doubles: 2^n segments in the rewrite reading.
    const auto meta = render_json("pl-lsys-lycopodium", "--set 'rule=F -> FF' --set reading=rewrite --set depth=5");
    CHECK(meta["panels"][0]["segments"] == 32);
    CHECK(meta["panels"][0]["plant"]["rules"] == nlohmann::json::array({"F -> FF"}));
}

TEST_CASE("malformed L-system rules are refused with one line naming the problem", "[plants]") {
    for (const char* bad : {"'rule=F -> F[+F'", "'rule=FF -> F'", "'rule=F FF'", "'rule=F -> F#'"}) {
        INFO(bad);
        const Run run = figgen(std::string("render pl-lsys-lycopodium --no-video --out ") +
                               out_dir("bad").string() + " --set " + bad);
        CHECK(run.status == 2);
        CHECK_THAT(run.output, Catch::StartsWith("figgen: error: "));
        CHECK(std::count(run.output.begin(), run.output.end(), '\n') == 1);
    }
    // Within the turtle's budget, the memory estimate refuses what does not fit.
    const Run deep = figgen("render pl-lsys-lycopodium --no-video --out " + out_dir("deep").string() +
                            " --set depth=7 --max-memory 1M");
    CHECK(deep.status == 2);
    CHECK_THAT(deep.output, Catch::Contains("of memory (plant of depth 7, 335922 segments: ") &&
                                Catch::Contains("more than --max-memory 1.0 MiB"));
    // Beyond it, the budget refuses it in phase 1, whatever the memory.
    const Run budget = figgen("render pl-lsys-lycopodium --no-video --out " + out_dir("deep").string() +
                              " --set depth=12 --max-memory 1000G");
    CHECK(budget.status == 2);
    CHECK_THAT(budget.output, Catch::Contains("segments, more than the budget of 800,000"));
}

TEST_CASE("the ABOP gallery draws the six plants with their closed-form segment counts", "[plants]") {
    const auto meta = render_json("pl-lsys-gallery", "");
    REQUIRE(meta["panels"].size() == 6);
    CHECK(meta["panels"][0]["segments"] == std::pow(5, 5));  // F -> F[+F]F[-F]F: 5 F per F
    CHECK(meta["panels"][1]["segments"] == std::pow(5, 5));  // F -> F[+F]F[-F][F]
    CHECK(meta["panels"][2]["segments"] == std::pow(8, 4));  // F -> FF-[-F+F+F]+[+F-F-F]: 8 F per F
}

TEST_CASE("the fern's points stay in the fern's known box", "[plants]") {
    const auto meta = render_json("pl-ifs-fern", "");
    // The published bounds of Barnsley's fern: -2.1820 < x < 2.6558, 0 <= y < 9.9983.
    const auto& bounds = meta["panels"][0]["points_bounds"];  // xmin, xmax, ymin, ymax
    CHECK(meta["panels"][0]["points"] == 200000);
    CHECK(bounds[0].get<double>() > -2.1821);
    CHECK(bounds[0].get<double>() < -2.0);
    CHECK(bounds[1].get<double>() < 2.6559);
    CHECK(bounds[1].get<double>() > 2.5);
    CHECK(bounds[2].get<double>() >= 0.0);
    CHECK(bounds[3].get<double>() < 9.9984);
    CHECK(bounds[3].get<double>() > 9.9);
    // The stem map (p = 0.01) is chosen about 1% of the time.
    const double stem = meta["panels"][0]["map_counts"][0].get<double>() / 200100.0;
    CHECK(stem == Approx(0.01).margin(0.002));
}

TEST_CASE("the sunflower places 240 seeds and 40 petals", "[plants]") {
    const auto meta = render_json("pl-phyllotaxis", "");
    REQUIRE(meta["panels"].size() == 3);
    CHECK(meta["panels"][0]["seeds"] == 240);
    CHECK(meta["panels"][0]["petals"] == 40);
    CHECK(meta["panels"][0]["outer_radius"].get<double>() == Approx(7 * std::sqrt(239.0)));
}
