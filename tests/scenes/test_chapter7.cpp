// The numbers of Think Complexity's chapter 7 as the figures compute them,
// against the book's values and the known results they approximate.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "description/catalog.hpp"
#include "description/description.hpp"
#include "figgen_run.hpp"
#include "app/render/render_figure.hpp"

namespace {

// Renders a catalog figure small and without video; returns its metadata.
nlohmann::json metadata_of(const std::string& id) {
    const auto d = description::load_description(description::resolve_figure(id));
    app::OutputOptions options;
    options.dir = std::filesystem::path(FIGGEN_TEST_ARTIFACT_DIR) / ("chapter7-" + std::to_string(::getpid()));
    options.scale = 0.25;
    options.video = false;
    scenes::Progress quiet;  // shows nothing
    app::render_figure(d, options, quiet);
    std::ifstream in(options.dir / (id + ".json"));
    auto meta = nlohmann::json::parse(in);
    std::filesystem::remove_all(options.dir);
    return meta;
}

}  // namespace

TEST_CASE("tc7-7 slopes are the book's 1.01 1.97 1.57 within 0.02", "[chapter7]") {
    const auto meta = metadata_of("tc7-7");
    REQUIRE(meta["panels"].size() == 3);
    CHECK(meta["panels"][0]["rule"] == 20);
    CHECK(meta["panels"][0]["slope"].get<double>() == Approx(1.01).margin(0.02));
    CHECK(meta["panels"][1]["slope"].get<double>() == Approx(1.97).margin(0.02));
    CHECK(meta["panels"][2]["slope"].get<double>() == Approx(1.57).margin(0.02));
    // Rule 50 from one cell: i + 1 cells in row i, so (n-1) n / 2 in 499 rows.
    CHECK(meta["panels"][1]["statistics"]["on_cells"] == 499 * 500 / 2);
}

TEST_CASE("tc7-9 cluster dimension lies near the book's 1.85 and the exact 91 over 48", "[chapter7]") {
    const auto meta = metadata_of("tc7-9");
    CHECK(meta["percolating_runs"].get<int>() >= 20);
    const double slope = meta["slope"];
    CHECK(slope > 1.75);
    CHECK(slope < 2.0);
    // The cluster can never hold fewer cells than a path down the array, nor more than the array.
    const auto& sizes = meta["sizes"];
    const auto& cells = meta["cluster_cells"];
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        const double n = sizes[i];
        CHECK(cells[i].get<double>() >= n - 1);
        CHECK(cells[i].get<double>() <= n * n - n);
    }
}

TEST_CASE("tc7-phase probabilities and the find_critical mean match the book", "[chapter7]") {
    const auto meta = metadata_of("tc7-phase");
    auto probability_at = [&](double q) {
        for (const auto& row : meta["probability"])
            if (std::abs(row["q"].get<double>() - q) < 1e-9) return row["probability"].get<double>();
        FAIL("q = " << q << " was not tried");
        return -1.0;
    };
    CHECK(probability_at(0.55) < 0.15);  // book: near 0
    CHECK(probability_at(0.60) > 0.45);  // book: about 0.7
    CHECK(probability_at(0.60) < 0.90);
    CHECK(probability_at(0.65) > 0.90);  // book: near 1
    // book: about 0.59; Newman & Ziff: 0.5927
    CHECK(meta["walk_mean"].get<double>() == Approx(0.5927).margin(0.015));
    CHECK(meta["walk"].size() == 101);
}

TEST_CASE("tc7-ex1 finds the known fractal rules and their dimensions", "[chapter7]") {
    const auto meta = metadata_of("tc7-ex1");
    REQUIRE(meta["rules"].size() == 256);
    auto row = [&](int rule) { return meta["rules"][rule]; };
    // Rules 18 and 90 from one cell draw Sierpinski's triangle: log2 3.
    CHECK(row(90)["slope_zero"].get<double>() == Approx(std::log2(3.0)).margin(0.02));
    CHECK(row(18)["slope_zero"].get<double>() == Approx(std::log2(3.0)).margin(0.02));
    // Rule 150's pattern has dimension log2(1 + sqrt 5) = 1.694.
    CHECK(row(150)["slope_zero"].get<double>() == Approx(std::log2(1 + std::sqrt(5.0))).margin(0.02));
    CHECK(row(90)["non_integer_zero"] == true);
    CHECK(row(150)["non_integer_zero"] == true);
    // A line, a solid triangle and a dead rule are not fractal.
    CHECK(row(20)["non_integer_zero"] == false);
    CHECK(row(50)["non_integer_zero"] == false);
    CHECK(row(0)["slope_zero"].get<double>() == 0.0);
    // The gallery lists exactly the rules flagged non-integer with either boundary.
    std::size_t flagged = 0;
    for (const auto& r : meta["rules"]) flagged += r["non_integer_zero"].get<bool>() || r["non_integer_wrap"].get<bool>();
    CHECK(meta["non_integer"].size() == flagged);
}

TEST_CASE("tc7-ex2 forest counts add up and its dimension is near 2", "[chapter7]") {
    const auto meta = metadata_of("tc7-ex2");
    for (const auto& panel : meta["panels"]) {
        const auto& s = panel["statistics"];
        CHECK(s["trees"].get<long>() + s["fires"].get<long>() + s["empty"].get<long>() == 200 * 200);
    }
    CHECK(meta["trees_over_time"].size() == 401);
    const double boxes = meta["box_counting"]["dimension"];
    CHECK(boxes > 1.5);
    CHECK(boxes <= 2.0);
    // The book's solution (trees in a centred box) finds it close to 2.
    CHECK(meta["central_box_mass"]["slope"].get<double>() == Approx(1.9).margin(0.1));
}

TEST_CASE("tc7-8 panels stop where test_perc stops", "[chapter7]") {
    const auto meta = metadata_of("tc7-8");
    REQUIRE(meta["panels"].size() == 3);
    int n = 100;
    for (const auto& panel : meta["panels"]) {
        CHECK(panel["n"] == n);
        const bool percolates = panel["statistics"]["percolates"];
        CHECK(panel["stopped"] == (percolates ? "bottom row wet" : "fixed point"));
        CHECK(panel["statistics"]["wet"].get<long>() >= n);  // the top row at least
        n += 100;
    }
}

TEST_CASE("tc7-2 to tc7-4 keep both chemicals within 0 and 1", "[chapter7]") {
    for (const char* id : {"tc7-2", "tc7-3", "tc7-4"}) {
        INFO(id);
        const auto meta = metadata_of(id);
        REQUIRE(meta["panels"].size() == 3);
        CHECK(meta["panels"][2]["step"] == 7000);
        for (const auto& panel : meta["panels"])
            for (const char* chemical : {"A", "B"}) {
                const auto& s = panel["statistics"][chemical];
                CHECK(s["min"].get<double>() >= 0.0);
                CHECK(s["max"].get<double>() <= 1.0);
                CHECK(s["min"].get<double>() <= s["mean"].get<double>());
                CHECK(s["mean"].get<double>() <= s["max"].get<double>());
            }
    }
}

TEST_CASE("a figure runs its model once and only to the last step an output needs", "[chapter7]") {
    // tc7-2's panels are at 1000, 3000 and 7000 and its film ends at 7000:
    // one run of 7000 steps serves both, not a run per panel (11,000) or more.
    const auto with_film = testkit::render_json("tc7-2", "--set animation.steps=[0,7000] --set animation.stride=1000");
    CHECK(with_film["model_steps"] == 7000);
    // tc7-1 without its film stops at its last panel, step 15, not at the film's 60.
    const auto no_film = testkit::render_json("tc7-1");
    CHECK(no_film["model_steps"] == 15);
    // With its film it runs on to the film's last step, 60, once.
    const auto out = testkit::fresh_dir("steps-film");
    const auto run = testkit::figgen("render tc7-1 --scale 0.25 --out " + out.string());
    REQUIRE(run.status == 0);
    std::ifstream in(out / "tc7-1.json");
    const auto film = nlohmann::json::parse(in);
    CHECK(film["model_steps"] == 60);
    CHECK(film["animation"]["frames"] == 61);
}
