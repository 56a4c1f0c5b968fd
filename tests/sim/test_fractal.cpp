#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "sim/cell1d.hpp"
#include "sim/fractal.hpp"

using sim::Grid;

namespace {

// Pascal's triangle mod 2 from a rule-90 run, each row i shifted left so
// that C(i, k) sits at column k (rule 90 puts it at centre - i + 2k).
Grid<std::uint8_t> pascal_from_rule_90(int rows) {
    sim::Cell1D ca(sim::Cell1DParams{90, rows, 0, sim::Boundary::zero});
    while (ca.rows_filled() < rows) ca.step();
    Grid<std::uint8_t> triangle(rows, rows, 0);
    for (int i = 0; i < rows; ++i)
        for (int k = 0; k <= i; ++k) triangle(i, k) = ca.cells()(i, rows - i + 2 * k);
    return triangle;
}

}  // namespace

TEST_CASE("fit_line recovers the slope and intercept of exact lines", "[fractal]") {
    std::vector<double> x, up, down, flat;
    for (int i = 0; i < 10; ++i) {
        x.push_back(i * 0.5 - 1);
        up.push_back(3 * x.back() - 2);
        down.push_back(-0.25 * x.back() + 7);
        flat.push_back(4);
    }
    const sim::LineFit a = sim::fit_line(x, up);
    CHECK(a.slope == Approx(3).epsilon(1e-14));
    CHECK(a.intercept == Approx(-2).epsilon(1e-14));
    CHECK(a.r == Approx(1).epsilon(1e-14));
    CHECK(a.points == 10);
    const sim::LineFit b = sim::fit_line(x, down);
    CHECK(b.slope == Approx(-0.25).epsilon(1e-14));
    CHECK(b.intercept == Approx(7).epsilon(1e-14));
    CHECK(b.r == Approx(-1).epsilon(1e-14));
    const sim::LineFit c = sim::fit_line(x, flat);
    CHECK(c.slope == 0);
    CHECK(c.intercept == 4);
    CHECK(c.r == 0);  // scipy's convention when y is constant
}

TEST_CASE("fit_line matches linregress on a scattered textbook example", "[fractal]") {
    // x 1..5, y 2 4 5 4 5: Sxy = 6, Sxx = 10, Syy = 6, so slope 0.6,
    // intercept 4 - 0.6 * 3 = 2.2 and r = 6 / sqrt(60).
    const std::vector<double> x = {1, 2, 3, 4, 5}, y = {2, 4, 5, 4, 5};
    const sim::LineFit fit = sim::fit_line(x, y);
    CHECK(fit.slope == Approx(0.6).epsilon(1e-15));
    CHECK(fit.intercept == Approx(2.2).epsilon(1e-15));
    CHECK(fit.r == Approx(6 / std::sqrt(60.0)).epsilon(1e-15));
}

TEST_CASE("fit_log_log recovers the exponent and prefactor of a power law", "[fractal]") {
    std::vector<double> x, y;
    for (int i = 1; i <= 20; ++i) {
        x.push_back(i);
        y.push_back(5 * std::pow(i, 1.5));
    }
    const sim::LineFit fit = sim::fit_log_log(x, y);
    CHECK(fit.slope == Approx(1.5).epsilon(1e-13));
    CHECK(fit.intercept == Approx(std::log(5.0)).epsilon(1e-13));
}

TEST_CASE("line fits refuse what has no line", "[fractal]") {
    const std::vector<double> one = {1}, two = {1, 2}, same = {3, 3}, three = {1, 2, 3};
    CHECK_THROWS_AS(sim::fit_line(one, one), std::invalid_argument);
    CHECK_THROWS_AS(sim::fit_line(same, two), std::invalid_argument);
    CHECK_THROWS_AS(sim::fit_line(two, three), std::invalid_argument);
    const std::vector<double> with_nan = {1, std::nan("")};
    CHECK_THROWS_AS(sim::fit_line(with_nan, two), std::invalid_argument);
    const std::vector<double> with_zero = {0, 1}, with_negative = {1, -2};
    CHECK_THROWS_AS(sim::fit_log_log(with_zero, two), std::invalid_argument);
    CHECK_THROWS_AS(sim::fit_log_log(two, with_negative), std::invalid_argument);
    CHECK_THROWS_AS(sim::fit_log_log(one, one), std::invalid_argument);
}

TEST_CASE("box counting a full grid gives dimension 2", "[fractal]") {
    const Grid<std::uint8_t> full(64, 64, 1);
    const sim::BoxCount count = sim::box_count(full, 1);
    CHECK(count.box_sizes == std::vector<int>{1, 2, 4, 8, 16});  // up to 64 / 4
    CHECK(count.occupied == std::vector<long>{4096, 1024, 256, 64, 16});
    CHECK(count.dimension == Approx(2).margin(1e-9));
    CHECK(count.fit.r == Approx(-1).margin(1e-12));
}

TEST_CASE("box counting a single row of cells gives dimension 1", "[fractal]") {
    Grid<std::uint8_t> grid(64, 64, 0);
    for (int j = 0; j < 64; ++j) grid(37, j) = 5;
    const sim::BoxCount count = sim::box_count(grid, 5);
    CHECK(count.occupied == std::vector<long>{64, 32, 16, 8, 4});
    CHECK(count.dimension == Approx(1).margin(1e-9));
}

TEST_CASE("box counting counts partial boxes at the right and bottom edges", "[fractal]") {
    Grid<std::uint8_t> grid(9, 10, 0);
    grid(8, 9) = 1;  // the far corner: only a partial box holds it at s = 2
    const sim::BoxCount count = sim::box_count(grid, 1, 2);
    CHECK(count.occupied == std::vector<long>{1, 1});
    CHECK(count.dimension == Approx(0).margin(1e-12));
}

TEST_CASE("box counting Sierpinski's triangle from rule 90 gives log2 of 3", "[fractal]") {
    const double log2_3 = std::log2(3.0);
    // As Pascal's right triangle, 2^8 rows: each aligned 2^m box is a copy of
    // the 2^m-row triangle or empty, so exactly 3^(8 - m) boxes are occupied.
    const sim::BoxCount pascal = sim::box_count(pascal_from_rule_90(256), 1, 128);
    REQUIRE(pascal.occupied.size() == 8);
    for (std::size_t m = 0; m < pascal.occupied.size(); ++m)
        CHECK(pascal.occupied[m] == static_cast<long>(std::pow(3, 8 - static_cast<int>(m))));
    CHECK(pascal.dimension == Approx(log2_3).margin(1e-12));
    // As the CA draws it: 256 rows x 513 columns, the on cells of a row on
    // every other column. A 1x1 box sees each cell alone, but from s = 2 on a
    // box bridges those one-column gaps and the counts fall by exactly 3 per
    // doubling; s = 1 sits off the line (6561 cells, 4374 boxes at s = 2),
    // which pulls the fit over all sizes down to 1.48.
    sim::Cell1D ca(sim::Cell1DParams{90, 256, 0, sim::Boundary::zero});
    while (ca.rows_filled() < 256) ca.step();
    const sim::BoxCount drawn = sim::box_count(ca.cells(), 1);
    CHECK(drawn.occupied == std::vector<long>{6561, 4374, 1458, 486, 162, 54, 18});
    const std::vector<double> sizes(drawn.box_sizes.begin() + 1, drawn.box_sizes.end());
    const std::vector<double> boxes(drawn.occupied.begin() + 1, drawn.occupied.end());
    CHECK(-sim::fit_log_log(sizes, boxes).slope == Approx(log2_3).margin(1e-12));
    CHECK(drawn.dimension == Approx(1.4778).margin(1e-4));  // sizes 1 .. 64
}

TEST_CASE("box counting refuses an empty state or a grid too small for two box sizes", "[fractal]") {
    CHECK_THROWS_AS(sim::box_count(Grid<std::uint8_t>(16, 16, 0), 1), std::invalid_argument);
    CHECK_THROWS_AS(sim::box_count(Grid<std::uint8_t>(7, 7, 1), 1), std::invalid_argument);
    CHECK_NOTHROW(sim::box_count(Grid<std::uint8_t>(8, 8, 1), 1));
}

TEST_CASE("central box mass of a full grid grows as size squared", "[fractal]") {
    const Grid<std::uint8_t> full(50, 60, 1);
    const sim::MassScaling mass = sim::central_box_mass(full, 1);
    REQUIRE(mass.sizes.size() == 25);  // 1, 3, ..., 49 < min(50, 60)
    for (std::size_t i = 0; i < mass.sizes.size(); ++i) {
        CHECK(mass.sizes[i] == static_cast<int>(2 * i + 1));
        CHECK(mass.mass[i] == long{mass.sizes[i]} * mass.sizes[i]);
    }
    CHECK(mass.fit.slope == Approx(2).margin(1e-12));
    CHECK(mass.fit.points == 25);
}

TEST_CASE("central box mass of a line through the centre grows as size", "[fractal]") {
    Grid<std::uint8_t> grid(51, 51, 0);
    for (int j = 0; j < 51; ++j) grid(25, j) = 1;
    const sim::MassScaling mass = sim::central_box_mass(grid, 1);
    for (std::size_t i = 0; i < mass.sizes.size(); ++i) CHECK(mass.mass[i] == mass.sizes[i]);
    CHECK(mass.fit.slope == Approx(1).margin(1e-12));
}

TEST_CASE("central box mass fits only the boxes that hold the state", "[fractal]") {
    Grid<std::uint8_t> grid(21, 21, 0);
    for (int i = 0; i < 21; ++i)
        for (int j = 0; j < 21; ++j) grid(i, j) = std::max(std::abs(i - 10), std::abs(j - 10)) >= 3;  // a 5x5 hole
    const sim::MassScaling mass = sim::central_box_mass(grid, 1);
    CHECK(mass.mass[0] == 0);  // sizes 1, 3 and 5 lie in the hole
    CHECK(mass.mass[2] == 0);
    CHECK(mass.mass[3] == 49 - 25);
    CHECK(mass.fit.points == mass.sizes.size() - 3);
    CHECK_THROWS_AS(sim::central_box_mass(Grid<std::uint8_t>(9, 9, 0), 1), std::invalid_argument);
}
