#include <catch2/catch.hpp>

#include <cmath>

#include "sim/phyllotaxis.hpp"

TEST_CASE("Vogel seeds sit at radius d sqrt n and angle n times the divergence", "[phyllotaxis]") {
    const sim::PhyllotaxisParams p{240, 137.508, 7};
    const auto seeds = sim::vogel_spiral(p);
    REQUIRE(seeds.size() == 240);
    CHECK(seeds[0].position == glm::dvec2(0, 0));
    for (int n : {1, 2, 57, 239}) {
        const auto& s = seeds[n];
        CHECK(glm::length(s.position) == Approx(7 * std::sqrt(double(n))).epsilon(1e-12));
        const double angle = std::fmod(n * 137.508, 360.0) * M_PI / 180.0;
        CHECK(std::atan2(s.position.y, s.position.x) ==
              Approx(angle > M_PI ? angle - 2 * M_PI : angle).margin(1e-9));
    }
    // Seed 1 at 137.508 degrees: (7 cos, 7 sin), worked out by hand.
    CHECK(seeds[1].position.x == Approx(7 * std::cos(137.508 * M_PI / 180)).epsilon(1e-12));
}

TEST_CASE("every Vogel seed claims the same area so the density is uniform", "[phyllotaxis]") {
    // Seeds within radius d sqrt(k) are exactly the first k: pi d^2 per seed.
    const auto seeds = sim::vogel_spiral({1000, 137.508, 1});
    for (int k : {10, 100, 500}) {
        int inside = 0;
        for (const auto& s : seeds) inside += glm::length(s.position) < std::sqrt(double(k)) - 1e-9;
        CHECK(inside == k);
    }
}

TEST_CASE("the golden angle keeps neighbours apart better than a rational-near angle", "[phyllotaxis]") {
    auto closest = [](double divergence) {
        const auto seeds = sim::vogel_spiral({500, divergence, 1});
        double best = 1e9;
        for (std::size_t i = 100; i < seeds.size(); ++i)
            for (std::size_t j = 0; j < i; ++j) best = std::min(best, glm::length(seeds[i].position - seeds[j].position));
        return best;
    };
    // 137.508 is the golden angle; 137.3 and 137.6 line seeds up into spokes.
    CHECK(closest(137.508) > closest(137.3));
    CHECK(closest(137.508) > closest(137.6));
}

TEST_CASE("phyllotaxis parameters are validated", "[phyllotaxis]") {
    CHECK_THROWS_WITH(sim::vogel_spiral({0, 137.5, 7}), "seeds = 0 is not allowed: an integer from 1 to 100000");
    CHECK_THROWS_WITH(sim::vogel_spiral({10, std::nan(""), 7}), Catch::StartsWith("divergence = nan is not allowed"));
}
