// The checks every model shares (sim/check.hpp).
#include <catch2/catch.hpp>

#include <cmath>

#include "sim/boundary.hpp"
#include "sim/check.hpp"

TEST_CASE("a parameter error names the parameter, its value, short, and what is allowed", "[check]") {
    try {
        sim::require_number("r", 1e308, 0.0, 0.25, "the stability bound");
        FAIL("1e308 accepted");
    } catch (const sim::ParameterError& e) {
        CHECK(e.name == "r");
        CHECK(e.value == "1e+308");
        CHECK(e.allowed == "a number from 0 to 0.25 (the stability bound)");
        CHECK(std::string(e.what()) == "r = 1e+308 is not allowed: a number from 0 to 0.25 (the stability bound)");
    }
    CHECK_THROWS_WITH(sim::require_integer("n", -3, 1, 8192), "n = -3 is not allowed: an integer from 1 to 8192");
    CHECK_NOTHROW(sim::require_number("r", 0.25, 0.0, 0.25));
    CHECK_THROWS_AS(sim::require_number("r", std::nan(""), 0.0, 0.25), sim::ParameterError);
    CHECK(sim::shown(0.1 + 0.2) == "0.3");
}

TEST_CASE("a field with a non-finite value stops the figure with an error", "[check]") {
    sim::Grid<double> field(3, 3, 0.5);
    CHECK_NOTHROW(sim::require_finite(field, "diffusion", 4));
    field(1, 2) = std::nan("");
    CHECK_THROWS_WITH(sim::require_finite(field, "gray_scott", 4),
                      "gray_scott went numerically unstable at step 4 (non-finite values); no image written");
    field(1, 2) = INFINITY;
    CHECK_THROWS(sim::require_finite(field, "diffusion", 4));
}
