#include <catch2/catch.hpp>

#include "sim/diffusion.hpp"
#include "sim/gray_scott.hpp"
#include "sim/stability.hpp"

namespace {
const sim::Kernel3 five_point = {0, 1, 0, 1, -4, 1, 0, 1, 0};
const sim::Kernel3 nine_point = {.05, .2, .05, .2, -1, .2, .05, .2, .05};
}  // namespace

TEST_CASE("the kernels' Fourier symbols give the bounds 0.25 and 1.25", "[stability]") {
    CHECK(sim::symbol_minimum(five_point, 16) == Approx(-8.0));
    CHECK(sim::stability_bound(five_point, 16) == Approx(0.25));
    CHECK(sim::symbol_minimum(nine_point, 16) == Approx(-1.6));
    CHECK(sim::stability_bound(nine_point, 16) == Approx(1.25));
}

TEST_CASE("a sweep of the rate finds the theoretical stability bounds within 0.005", "[stability]") {
    // Below the bound nothing grows; the first rate past it amplifies the checkerboard.
    CHECK(sim::amplification(five_point, 0.245, 16, 200) <= 1.0);
    CHECK(sim::amplification(five_point, 0.255, 16, 200) > 1.0);
    CHECK(sim::empirical_bound(five_point, 0.2, 0.005, 16, 200) == Approx(0.255).margin(0.0051));
    CHECK(sim::amplification(nine_point, 1.245, 16, 200) <= 1.0);
    CHECK(sim::amplification(nine_point, 1.255, 16, 200) > 1.0);
    CHECK(sim::empirical_bound(nine_point, 1.0, 0.005, 16, 200) == Approx(1.255).margin(0.0051));
}

TEST_CASE("rates beyond the bounds are refused before a model runs", "[stability]") {
    sim::DiffusionParams d;
    d.r = 0.2501;
    CHECK_THROWS_WITH(d.validate(), "r = 0.2501 is not allowed: a number from 0 to 0.25 (the explicit 5-point update's stability bound; beyond it the checkerboard grows)");
    // Gray-Scott allows up to 1, the monotone bound (no new extremes), inside the L2 bound 1.25.
    sim::GrayScottParams g;
    g.ra = 1.3;
    CHECK_THROWS_WITH(g.validate(), "ra = 1.3 is not allowed: a number from 0 to 1 (the 9-point diffusion is monotone up to 1, no new extremes, and blows up beyond 1.25)");
}
