#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "sim/gray_scott.hpp"
#include "sim/random.hpp"

using sim::GrayScott;
using sim::GrayScottParams;
using sim::Grid;

namespace {

GrayScottParams quiet(int n) {  // the book's rates, no noise
    GrayScottParams p;
    p.n = n;
    p.noise = 0.0;
    return p;
}

double total(const Grid<double>& g) { return std::accumulate(g.cells().begin(), g.cells().end(), 0.0); }

bool within_unit_interval(const Grid<double>& g) {
    return std::all_of(g.cells().begin(), g.cells().end(), [](double v) { return v >= 0.0 && v <= 1.0; });
}

}  // namespace

TEST_CASE("gray-scott starts with A at 1 and B noise plus the book's central island", "[gray_scott]") {
    GrayScottParams p;  // n 100: r = 5, island rows and columns 45 .. 54
    sim::Random rng(7), reference(7);
    const GrayScott model(p, rng);
    for (int i = 0; i < p.n; ++i)
        for (int j = 0; j < p.n; ++j) {
            const bool island = i >= 45 && i < 55 && j >= 45 && j < 55;
            const double noise = 0.1 * reference.uniform();  // drawn row by row
            REQUIRE(model.a()(i, j) == 1.0);
            REQUIRE(model.b()(i, j) == (island ? noise + 0.1 : noise));
        }
    CHECK(rng.next() == reference.next());  // exactly n * n draws
    CHECK(model.steps() == 0);
}

TEST_CASE("gray-scott's first step equals the values worked out by hand", "[gray_scott]") {
    // 4 x 4 torus, book rates (ra .5, rb .25, f .035, k .057). B = 0.5 at
    // (0, 0) and 0 elsewhere; A = 1 except 0.5 at (2, 2), which is not a
    // neighbour of (0, 0) on this torus.
    const GrayScottParams p = quiet(4);
    Grid<double> a(4, 4, 1.0), b(4, 4, 0.0);
    a(2, 2) = 0.5;
    b(0, 0) = 0.5;
    GrayScott model(p, a, b);
    model.step();
    const auto& na = model.a();
    const auto& nb = model.b();
    // (0, 0): cA = 0, reaction = 1 * 0.25; cB = -0.5.
    CHECK(na(0, 0) == Approx(1 - 0.25).epsilon(1e-15));
    CHECK(nb(0, 0) == Approx(0.5 + 0.25 * -0.5 + 0.25 - 0.092 * 0.5).epsilon(1e-15));  // 0.579
    // B's edge neighbours get rb * 0.2 * 0.5 = 0.025, across the wrap too.
    CHECK(nb(0, 1) == Approx(0.025).epsilon(1e-15));
    CHECK(nb(3, 0) == Approx(0.025).epsilon(1e-15));
    CHECK(nb(0, 3) == Approx(0.025).epsilon(1e-15));
    // Corner neighbours get rb * 0.05 * 0.5 = 0.00625, (3, 3) through both wraps.
    CHECK(nb(1, 1) == Approx(0.00625).epsilon(1e-15));
    CHECK(nb(3, 3) == Approx(0.00625).epsilon(1e-15));
    CHECK(nb(2, 2) == 0.0);
    CHECK(nb(2, 0) == 0.0);
    // (2, 2): cA = 0.2 + 0.8 - 0.5 = 0.5, no B: 0.5 + 0.5 * 0.5 + 0.035 * 0.5 = 0.7675.
    CHECK(na(2, 2) == Approx(0.7675).epsilon(1e-15));
    // (1, 2), edge neighbour of (2, 2): cA = 0.2 + 0.2 * 3.5 - 1 = -0.1 -> 0.95.
    CHECK(na(1, 2) == Approx(0.95).epsilon(1e-15));
    // (1, 1), corner neighbour: cA = 0.05 * 3.5 + 0.8 - 1 = -0.025 -> 0.9875.
    CHECK(na(1, 1) == Approx(0.9875).epsilon(1e-15));
    CHECK(na(3, 3) == Approx(0.9875).epsilon(1e-15));
    CHECK(model.steps() == 1);
}

TEST_CASE("gray-scott's uniform state A 1 B 0 is an exact fixed point", "[gray_scott]") {
    const GrayScottParams p = quiet(16);
    const Grid<double> a(16, 16, 1.0), b(16, 16, 0.0);
    GrayScott model(p, a, b);
    for (int s = 0; s < 100; ++s) model.step();
    CHECK(model.a() == a);
    CHECK(model.b() == b);
}

TEST_CASE("gray-scott without noise keeps the island's mirror and rotation symmetries bit for bit", "[gray_scott]") {
    // n even: the island covers [n/2 - r, n/2 + r), symmetric about (n - 1) / 2
    // like the grid, so i -> n-1-i, j -> n-1-j and the quarter turn
    // (i, j) -> (n-1-j, i) all map the start onto itself.
    for (const auto& [f, k] : {std::pair{0.035, 0.057}, std::pair{0.055, 0.062}, std::pair{0.039, 0.065}}) {
        GrayScottParams p = quiet(64);
        p.island = 0.2;  // without noise the book's 0.1 island fades away; from about 0.35 B overshoots 1 at first
        p.f = f;
        p.k = k;
        sim::Random unused(1);
        GrayScott model(p, unused);
        const int n = p.n;
        for (int s = 1; s <= 1500; ++s) {
            model.step();
            REQUIRE(within_unit_interval(model.a()));
            REQUIRE(within_unit_interval(model.b()));
            if (s % 250 != 0) continue;
            for (const Grid<double>* g : {&model.a(), &model.b()})
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        INFO("f " << f << " step " << s << " cell " << i << " " << j);
                        REQUIRE((*g)(i, j) == (*g)(i, n - 1 - j));
                        REQUIRE((*g)(i, j) == (*g)(n - 1 - i, j));
                        REQUIRE((*g)(i, j) == (*g)(n - 1 - j, i));
                    }
        }
        // Not trivially symmetric: B has spread into a pattern.
        const auto [low, high] = std::minmax_element(model.b().cells().begin(), model.b().cells().end());
        CHECK(*high - *low > 0.05);
    }
}

TEST_CASE("gray-scott with f and k zero conserves the total of A plus B on the torus", "[gray_scott]") {
    // The kernel sums to zero, so diffusion moves mass around the torus;
    // the reaction A B^2 moves it from A to B; with f = k = 0 nothing is fed or removed.
    GrayScottParams p;
    p.n = 48;
    p.f = 0.0;
    p.k = 0.0;
    p.noise = 0.5;
    p.island = 0.4;
    sim::Random rng(11);
    GrayScott model(p, rng);
    const double start = total(model.a()) + total(model.b());
    for (int s = 0; s < 2000; ++s) {
        model.step();
        REQUIRE(total(model.a()) + total(model.b()) == Approx(start).epsilon(1e-12));
    }
    CHECK(total(model.b()) > 0.5 * start);  // the reaction did move mass from A to B
}

TEST_CASE("shifting gray-scott's start around the torus shifts every later state exactly", "[gray_scott]") {
    // Translation covariance: every cell, at the edge or inside, does the same
    // arithmetic in the same order, so no cell of the torus is special.
    GrayScottParams p;
    p.n = 40;
    sim::Random rng(3);
    GrayScott original(p, rng);
    const int n = p.n, dr = 7, dc = 33;
    Grid<double> a(n, n), b(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            a((i + dr) % n, (j + dc) % n) = original.a()(i, j);
            b((i + dr) % n, (j + dc) % n) = original.b()(i, j);
        }
    GrayScott shifted(p, a, b);
    for (int s = 0; s < 300; ++s) {
        original.step();
        shifted.step();
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            REQUIRE(shifted.a()((i + dr) % n, (j + dc) % n) == original.a()(i, j));
            REQUIRE(shifted.b()((i + dr) % n, (j + dc) % n) == original.b()(i, j));
        }
}

TEST_CASE("gray-scott's three figure runs keep both chemicals within 0 and 1", "[gray_scott]") {
    for (const auto& [f, k] : {std::pair{0.035, 0.057}, std::pair{0.055, 0.062}, std::pair{0.039, 0.065}}) {
        GrayScottParams p;
        p.f = f;
        p.k = k;
        sim::Random rng(17);
        GrayScott model(p, rng);
        for (int s = 0; s < 3000; ++s) {
            model.step();
            INFO("f " << f << " k " << k << " step " << model.steps());
            REQUIRE(within_unit_interval(model.a()));
            REQUIRE(within_unit_interval(model.b()));
        }
    }
}

TEST_CASE("gray-scott parameters are validated with messages naming them", "[gray_scott]") {
    auto message_of = [](GrayScottParams p) {
        try {
            p.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    GrayScottParams p;
    CHECK(message_of(p) == "accepted");
    p.ra = 1.0;  // the edge of monotonicity is allowed
    CHECK(message_of(p) == "accepted");
    p.ra = 1.1;
    CHECK(message_of(p) == "ra = 1.1 is not allowed: a number from 0 to 1 (the 9-point diffusion is monotone up to 1, no new extremes, and blows up beyond 1.25)");
    p = GrayScottParams{};
    p.k = std::nan("");
    CHECK(message_of(p).rfind("k = nan is not allowed", 0) == 0);
    p = GrayScottParams{};
    p.n = 2;
    CHECK(message_of(p) == "n = 2 is not allowed: an integer from 3 to 4096");
    p = GrayScottParams{};
    p.f = 0.3;
    CHECK(message_of(p) == "f = 0.3 is not allowed: a number from 0 to 0.2");
    p = GrayScottParams{};
    p.noise = -0.1;
    CHECK(message_of(p) == "noise = -0.1 is not allowed: a number from 0 to 1");
    CHECK_THROWS_AS(GrayScott(GrayScottParams{}, Grid<double>(4, 4), Grid<double>(4, 4)), std::invalid_argument);
    Grid<double> bad(3, 3, 1.0);
    bad(1, 1) = INFINITY;
    CHECK_THROWS_AS(GrayScott(quiet(3), bad, Grid<double>(3, 3)), std::invalid_argument);
}
