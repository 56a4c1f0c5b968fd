#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/ifs.hpp"
#include "sim/random.hpp"

using sim::AffineMap;
using sim::ChaosGameParams;
using sim::Ifs;

namespace {

std::string message_of(const Ifs& ifs) {
    try {
        ifs.validate();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("the fern's points stay inside its published bounding box", "[ifs]") {
    // Published bounds of the Barnsley fern's attractor: -2.1820 < x < 2.6558, 0 <= y < 9.9983.
    sim::Random rng(1);
    const auto points = sim::chaos_game(sim::barnsley_fern(), ChaosGameParams{}, rng);
    REQUIRE(points.size() == 200000);
    double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
    for (const auto& v : points) {
        min_x = std::min(min_x, v.x);
        max_x = std::max(max_x, v.x);
        min_y = std::min(min_y, v.y);
        max_y = std::max(max_y, v.y);
    }
    const double slack = 1e-9;
    CHECK(min_x > -2.1820 - slack);
    CHECK(max_x < 2.6558 + slack);
    CHECK(min_y >= 0 - slack);
    CHECK(max_y < 9.9983 + slack);
    // And the cloud fills most of that box, so the bounds are not passed trivially.
    CHECK(min_x < -2.0);
    CHECK(max_x > 2.5);
    CHECK(max_y > 9.9);
}

TEST_CASE("the chaos game takes one uniform a step and picks maps by cumulative probability", "[ifs]") {
    // An independent replay: the same stream, the cumulative table written out by hand.
    const Ifs fern = sim::barnsley_fern();
    sim::Random rng(42), reference(42);
    std::vector<std::uint64_t> counts;
    const auto points = sim::chaos_game(fern, ChaosGameParams{1000, 10, {0.5, 0.5}}, rng, &counts);
    glm::dvec2 v{0.5, 0.5};
    std::vector<std::uint64_t> expected_counts(4, 0);
    for (int s = 0; s < 1010; ++s) {
        const double u = reference.uniform();
        const int m = u < 0.01 ? 0 : u < 0.86 ? 1 : u < 0.93 ? 2 : 3;
        ++expected_counts[m];
        const AffineMap& f = fern.maps[m];
        v = {f.a * v.x + f.b * v.y + f.e, f.c * v.x + f.d * v.y + f.f};
        if (s >= 10) REQUIRE(points[s - 10] == v);
    }
    CHECK(counts == expected_counts);
    CHECK(rng.next() == reference.next());  // nothing else was drawn
}

TEST_CASE("map choice frequencies match the probabilities within 5 standard errors", "[ifs]") {
    const Ifs fern = sim::barnsley_fern();
    sim::Random rng(2024);
    std::vector<std::uint64_t> counts;
    const std::uint64_t n = 1000000;
    sim::chaos_game(fern, ChaosGameParams{n, 0, {0, 0}}, rng, &counts);
    REQUIRE(counts.size() == 4);
    for (std::size_t m = 0; m < 4; ++m) {
        const double p = fern.maps[m].p;
        const double se = std::sqrt(p * (1 - p) / n);
        INFO("map " << m << " count " << counts[m]);
        CHECK(std::abs(static_cast<double>(counts[m]) / n - p) < 5 * se);
    }
}

TEST_CASE("a map with probability zero is never picked", "[ifs]") {
    Ifs ifs{{{0.5, 0, 0, 0.5, 0, 0, 0.5}, {0.5, 0, 0, 0.5, 1, 0, 0.0}, {0.5, 0, 0, 0.5, 0, 1, 0.5}}};
    sim::Random rng(3);
    std::vector<std::uint64_t> counts;
    sim::chaos_game(ifs, ChaosGameParams{10000, 0, {0, 0}}, rng, &counts);
    CHECK(counts[1] == 0);
    CHECK(counts[0] + counts[2] == 10000);
    CHECK(sim::pick_map(ifs, 0.0) == 0);
    CHECK(sim::pick_map(ifs, 0.5) == 2);
    CHECK(sim::pick_map(ifs, 1.0 - 0x1.0p-53) == 2);
    // A total a hair under 1 (allowed by validate) still picks the last positive map for u above it.
    Ifs short_sum{{{0.5, 0, 0, 0.5, 0, 0, 0.5}, {0.5, 0, 0, 0.5, 1, 0, 0.5 - 1e-10}, {0.5, 0, 0, 0.5, 0, 1, 0.0}}};
    REQUIRE(message_of(short_sum) == "accepted");
    CHECK(sim::pick_map(short_sum, 1.0 - 0x1.0p-53) == 1);
}

TEST_CASE("the same seed gives the same points and different seeds differ", "[ifs]") {
    const Ifs fern = sim::barnsley_fern();
    const ChaosGameParams p{5000, 100, {0, 0}};
    sim::Random a(7), b(7), c(8);
    const auto pa = sim::chaos_game(fern, p, a);
    const auto pb = sim::chaos_game(fern, p, b);
    const auto pc = sim::chaos_game(fern, p, c);
    CHECK(pa == pb);
    CHECK(pa != pc);
}

TEST_CASE("a single contraction converges to its fixed point", "[ifs]") {
    // x' = 0.5 x + 1, y' = -0.3 y - 2.6: fixed point (2, -2), reached to rounding in ~60 halvings.
    const Ifs one{{{0.5, 0, 0, -0.3, 1, -2.6, 1.0}}};
    sim::Random rng(5);
    const auto points = sim::chaos_game(one, ChaosGameParams{10, 100, {1000, -500}}, rng);
    REQUIRE(points.size() == 10);
    for (const auto& v : points) {
        CHECK(v.x == Approx(2.0).margin(1e-12));
        CHECK(v.y == Approx(-2.0).margin(1e-12));
    }
    // Without the discard the first points still show the start's pull, halving each step.
    sim::Random again(5);
    const auto early = sim::chaos_game(one, ChaosGameParams{3, 0, {1002, -2}}, again);
    CHECK(early[0].x == 2 + 500.0);
    CHECK(early[1].x == 2 + 250.0);
    CHECK(early[2].x == 2 + 125.0);
}

TEST_CASE("ifs validation names the bad map, coefficient or sum in one line", "[ifs]") {
    CHECK(message_of(sim::barnsley_fern()) == "accepted");
    CHECK(message_of(Ifs{}) == "maps = 0 is not allowed: an integer from 1 to 64");
    CHECK(message_of(Ifs{std::vector<AffineMap>(65, AffineMap{0.5, 0, 0, 0.5, 0, 0, 1.0 / 65})}) ==
          "maps = 65 is not allowed: an integer from 1 to 64");
    Ifs bad = sim::barnsley_fern();
    bad.maps[2].b = std::nan("");
    CHECK(message_of(bad) == "maps[2].b = nan is not allowed: a finite number");
    bad = sim::barnsley_fern();
    bad.maps[1].f = INFINITY;
    CHECK(message_of(bad) == "maps[1].f = inf is not allowed: a finite number");
    bad = sim::barnsley_fern();
    bad.maps[3].p = -0.07;
    CHECK(message_of(bad) == "maps[3].p = -0.07 is not allowed: a number from 0 to 1");
    bad = sim::barnsley_fern();
    bad.maps[1].p = 0.82;
    CHECK(message_of(bad) ==
          "maps = probabilities summing to 0.97 is not allowed: probabilities p summing to 1 (within 1e-9)");
    sim::Random rng(1);
    CHECK_THROWS_AS(sim::chaos_game(bad, ChaosGameParams{}, rng), std::invalid_argument);
    ChaosGameParams p;
    p.points = 100000001;
    CHECK_THROWS_WITH(sim::chaos_game(sim::barnsley_fern(), p, rng),
                      "points = 100000001 is not allowed: an integer from 0 to 100000000");
    p = ChaosGameParams{};
    p.start.y = NAN;
    CHECK_THROWS_WITH(sim::chaos_game(sim::barnsley_fern(), p, rng),
                      "start.y = nan is not allowed: a number from -1e+300 to 1e+300");
}

TEST_CASE("density counts every point inside the box once, row 0 at the top", "[ifs]") {
    sim::Random rng(11);
    const auto points = sim::chaos_game(sim::barnsley_fern(), ChaosGameParams{50000, 100, {0, 0}}, rng);
    // A box that cuts the fern, so some points fall outside.
    const glm::dvec2 lo{-1.0, 1.0}, hi{2.0, 8.0};
    const auto d = sim::density(points, 60, 140, lo, hi);
    REQUIRE(d.counts.size() == 60u * 140u);
    std::uint64_t inside = 0;
    for (const auto& v : points) inside += v.x >= lo.x && v.x <= hi.x && v.y >= lo.y && v.y <= hi.y;
    std::uint64_t total = 0;
    for (std::uint32_t c : d.counts) total += c;
    CHECK(total == inside);
    CHECK(inside < points.size());
    CHECK(inside > points.size() / 2);

    // Pixel placement, edges included: corners and a point in the top-left pixel.
    const std::vector<glm::dvec2> corners{{0, 0}, {4, 0}, {0, 2}, {4, 2}, {0.5, 1.9}, {4.1, 1}, {1, -0.1}};
    const auto c = sim::density(corners, 4, 2, {0, 0}, {4, 2});
    CHECK(c.at(1, 0) == 1);  // (0, 0): bottom-left
    CHECK(c.at(1, 3) == 1);  // (4, 0): bottom-right, hi.x belongs to the last column
    CHECK(c.at(0, 0) == 2);  // (0, 2) and (0.5, 1.9): top-left
    CHECK(c.at(0, 3) == 1);  // (4, 2): top-right
    CHECK(c.at(0, 1) + c.at(0, 2) + c.at(1, 1) + c.at(1, 2) == 0);
    CHECK_THROWS_WITH(sim::density(corners, 0, 2, {0, 0}, {4, 2}),
                      "width = 0 is not allowed: an integer from 1 to 16384");
    CHECK_THROWS_AS(sim::density(corners, 4, 2, {0, 0}, {0, 2}), std::invalid_argument);
}
