// The sf87 figures as a user drives them: rule codes on the command line,
// refused codes, and the metadata each panel records.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"

namespace fs = std::filesystem;

using testkit::figgen;
using testkit::render_json;
using testkit::Run;

TEST_CASE("any valid rule code can be set from the command line", "[sf87]") {
    // 0110000 freezes on one or two neighbours: the full hexagon, 3t(t+1)+1 cells after t steps.
    const auto meta = render_json("sf87-3", "--set rule=0110000 --set steps=10");
    REQUIRE(meta["panels"].size() == 2);
    for (const auto& panel : meta["panels"]) {
        CHECK(panel["rule"] == "0110000");
        CHECK(panel["step"] == 10);
        CHECK(panel["statistics"]["ice"] == 3 * 10 * 11 + 1);
        CHECK(panel["statistics"]["radius"] == 10);
    }
}

TEST_CASE("the metadata says how far the crystals grew when panels ask past params.steps", "[sf87]") {
    // 0110000 fills the hexagon: 3t(t+1)+1 cells after t steps, whatever params.steps says.
    // Four panels at scale 0.3 hold captions of a label each, not the whole sentence.
    const auto meta = render_json("sf87-3", "--set rule=0110000 --set steps=5 --set figure.panels=[4,12] "
                                            "--set style.caption={label}");
    CHECK(meta["steps_run"] == 12);
    REQUIRE(meta["panels"].size() == 4);
    CHECK(meta["panels"][3]["step"] == 12);
    CHECK(meta["panels"][3]["statistics"]["ice"] == 3 * 12 * 13 + 1);
    for (const auto& run : meta["runs"]) CHECK(run["rule"] == "0110000");  // each run's rule as run
}

TEST_CASE("malformed or plane-filling rule codes are refused with the reason", "[sf87]") {
    struct Case {
        std::string code, reason;
    };
    for (const Case& c : {Case{"0102010", "7 binary digits"}, Case{"01010", "7 binary digits"},
                          Case{"1100000", "d0 = 1"}}) {
        INFO(c.code);
        const Run run = figgen("render sf87-3 --no-video --out " +
                               (fs::path(FIGGEN_TEST_ARTIFACT_DIR) / "sf87" / "refused").string() +
                               " --set rule=" + c.code);
        CHECK(run.status == 2);
        CHECK_THAT(run.output, Catch::StartsWith("figgen: error: ") && Catch::Contains(c.reason));
        CHECK(std::count(run.output.begin(), run.output.end(), '\n') == 1);
    }
}

TEST_CASE("restriction and priority settings are recorded per panel", "[sf87]") {
    const auto four = render_json("sf87-4", "");
    REQUIRE(four["panels"].size() == 2);
    CHECK(four["panels"][0]["rule"] == "0100000");
    CHECK(four["panels"][0]["restriction"]["steps"] == nlohmann::json::array({1, 16}));
    CHECK(four["panels"][1]["restriction"]["steps"] == nlohmann::json::array({5, 22}));
    CHECK(four["panels"][0]["restriction"]["half_angle_degrees"] == 15.0);
    const auto five = render_json("sf87-5", "");
    REQUIRE(five["panels"].size() == 3);
    CHECK(five["panels"][0]["priority"]["steps"] == nlohmann::json::array({4, 5}));
    CHECK(five["panels"][1]["priority"]["steps"] == nlohmann::json::array({4}));
    CHECK(five["panels"][2]["priority"]["steps"] == nlohmann::json::array({7, 8}));
}

TEST_CASE("sf87-6 shows one crystal growing at steps 19 23 27", "[sf87]") {
    const auto meta = render_json("sf87-6", "");
    REQUIRE(meta["panels"].size() == 3);
    long previous = 0;
    int expected_step = 19;
    for (const auto& panel : meta["panels"]) {
        CHECK(panel["step"] == expected_step);
        CHECK(panel["statistics"]["radius"] == expected_step);  // 0101010's arms grow a ring a step
        CHECK(panel["statistics"]["ice"].get<long>() > previous);
        previous = panel["statistics"]["ice"];
        expected_step += 4;
    }
}

TEST_CASE("sf87-dim fits a dimension for every rule over a stated range", "[sf87]") {
    const auto meta = render_json("sf87-dim", "");
    REQUIRE(meta["fits"].size() == 5);
    for (const auto& fit : meta["fits"]) {
        INFO(fit.dump());
        const double dimension = fit["dimension"];
        CHECK(dimension > 1.5);
        CHECK(dimension < 2.1);
        CHECK(fit["fit_range"][0] == 4);
        CHECK(fit["fit_range"][1].get<int>() > 20);
    }
}
