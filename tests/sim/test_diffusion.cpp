#include <catch2/catch.hpp>

#include <cmath>

#include "sim/diffusion.hpp"

using sim::Diffusion;
using sim::DiffusionParams;

namespace {
DiffusionParams book() { return DiffusionParams{}; }  // n 9, r 0.1, zero-fill, 3x3 block of 1 at (3, 3)
}  // namespace

TEST_CASE("diffusion's first steps equal the values worked out by hand", "[diffusion]") {
    Diffusion d(book());
    const auto& a = d.field();
    CHECK(a(4, 4) == 1.0);
    CHECK(a(2, 4) == 0.0);
    d.step();
    // Step 1, a += 0.1 * (sum of 4 neighbours - 4 a):
    CHECK(a(4, 4) == Approx(1.0).epsilon(1e-15));  // inside: 4 - 4 = 0
    CHECK(a(3, 4) == Approx(0.9).epsilon(1e-15));  // block edge: 3 - 4 = -1
    CHECK(a(3, 3) == Approx(0.8).epsilon(1e-15));  // block corner: 2 - 4 = -2
    CHECK(a(2, 4) == Approx(0.1).epsilon(1e-15));  // just outside: 1 - 0
    CHECK(a(2, 2) == 0.0);                         // diagonal neighbours do not count
    CHECK(a(1, 4) == 0.0);
    d.step();
    // Step 2: centre 1 + 0.1 * (4 * 0.9 - 4) = 0.96; (1, 4) gets 0.1 * 0.1 = 0.01;
    // (2, 4): 0.1 + 0.1 * (0.9 + 0 + 0 + 0 - 0.4) = 0.15 (neighbours (2,3), (2,5) are 0.1 each):
    CHECK(a(4, 4) == Approx(0.96).epsilon(1e-14));
    CHECK(a(1, 4) == Approx(0.01).epsilon(1e-14));
    CHECK(a(2, 4) == Approx(0.1 + 0.1 * (0.9 + 0.1 + 0.1 + 0.0 - 0.4)).epsilon(1e-14));
    CHECK(d.steps() == 2);
}

TEST_CASE("wrap conserves the total and zero-fill loses it once mass reaches the edge", "[diffusion]") {
    DiffusionParams wrap = book();
    wrap.boundary = sim::Boundary::wrap;
    Diffusion w(wrap), z(book());
    double previous = z.total();
    for (int i = 0; i < 200; ++i) {
        w.step();
        z.step();
        REQUIRE(w.total() == Approx(9.0).epsilon(1e-12));
        REQUIRE(z.total() <= previous * (1 + 1e-14));  // never gains (beyond rounding of the sum)
        previous = z.total();
    }
    // The block's edge is 3 cells from the border: nothing leaves for 3 steps.
    Diffusion early(book());
    for (int i = 0; i < 3; ++i) early.step();
    CHECK(early.total() == Approx(9.0).epsilon(1e-14));
    CHECK(z.total() < 1.0);  // after 200 steps most has leaked out
}

TEST_CASE("a Fourier mode on the torus decays by the exact discrete factor", "[diffusion]") {
    // a = cos(2 pi k i / n) is an eigenvector of the wrapped 5-point Laplacian
    // with eigenvalue 2 cos(2 pi k / n) - 2, so one step multiplies it by
    // 1 + r (2 cos(2 pi k / n) - 2).
    DiffusionParams p;
    p.n = 32;
    p.r = 0.2;
    p.boundary = sim::Boundary::wrap;
    const int k = 3;
    sim::Grid<double> initial(p.n, p.n);
    for (int i = 0; i < p.n; ++i)
        for (int j = 0; j < p.n; ++j) initial(i, j) = std::cos(2 * M_PI * k * i / p.n);
    Diffusion d(p, initial);
    const double factor = 1 + p.r * (2 * std::cos(2 * M_PI * k / p.n) - 2);
    for (int s = 0; s < 10; ++s) d.step();
    for (int i = 0; i < p.n; ++i)
        REQUIRE(d.field()(i, 5) == Approx(std::pow(factor, 10) * initial(i, 5)).margin(1e-12));
}

TEST_CASE("diffusion stays symmetric and bounded at the stability limit", "[diffusion]") {
    DiffusionParams p = book();
    p.r = 0.25;
    Diffusion d(p);
    for (int s = 0; s < 500; ++s) d.step();
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) {
            REQUIRE(d.field()(i, j) >= 0.0);
            REQUIRE(d.field()(i, j) <= 1.0);
            REQUIRE(d.field()(i, j) == Approx(d.field()(j, i)).margin(1e-15));
            REQUIRE(d.field()(i, j) == Approx(d.field()(8 - i, j)).margin(1e-15));
        }
}

TEST_CASE("diffusion parameters are validated with messages naming them", "[diffusion]") {
    auto message_of = [](DiffusionParams p) {
        try {
            p.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    DiffusionParams p = book();
    p.r = 0.3;
    CHECK(message_of(p) == "r = 0.3 is not allowed: a number from 0 to 0.25 (the explicit 5-point update's stability bound; beyond it the checkerboard grows)");
    p.r = std::nan("");
    CHECK(message_of(p).rfind("r = nan is not allowed", 0) == 0);
    p = book();
    p.n = -4;
    CHECK(message_of(p) == "n = -4 is not allowed: an integer from 1 to 8192");
    p = book();
    p.block_row = 7;  // a 3-cell block from row 7 leaves a 9-cell grid
    CHECK(message_of(p) == "block_row = 7 is not allowed: an integer from 0 to 6");
    CHECK(message_of(book()) == "accepted");
    CHECK_THROWS_AS(Diffusion(book(), sim::Grid<double>(4, 4)), std::invalid_argument);
}
