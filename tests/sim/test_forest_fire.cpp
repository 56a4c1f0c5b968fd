#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "sim/forest_fire.hpp"
#include "sim/random.hpp"

using sim::ForestFire;
using sim::ForestFireParams;
using sim::Grid;

namespace {

constexpr std::uint8_t empty = 0, tree = 1, fire = 5;

std::uint64_t fnv1a(const Grid<std::uint8_t>& g) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (std::uint8_t c : g.cells()) h = (h ^ c) * 0x100000001b3ULL;
    return h;
}

long count(const Grid<std::uint8_t>& g, std::uint8_t state) {
    return static_cast<long>(std::count(g.cells().begin(), g.cells().end(), state));
}

ForestFireParams lively(int n) {  // fast growth and lightning so that every transition happens
    return ForestFireParams{n, 0.05, 0.01, 0.5};
}

}  // namespace

TEST_CASE("forest fire plants trees with one draw per cell and counts the states", "[forest_fire]") {
    const ForestFire model(ForestFireParams{20, 0.01, 0.001, 0.3}, 99);
    sim::Random reference(99);
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) REQUIRE(model.cells()(i, j) == (reference.uniform() < 0.3 ? tree : empty));
    CHECK(model.trees() == count(model.cells(), tree));
    CHECK(model.fires() == 0);
    CHECK(model.empties() == 400 - model.trees());
    CHECK(model.steps() == 0);
}

TEST_CASE("forest fire steps follow the three rules with one draw per cell in row order", "[forest_fire]") {
    // An independent reading of the rules against the same stream: n * n
    // draws to plant, then n * n per step whatever each cell holds.
    const ForestFireParams p = lively(30);
    const std::uint64_t seed = 12;
    ForestFire model(p, seed);
    sim::Random reference(seed);
    for (int c = 0; c < 30 * 30; ++c) reference.uniform();
    for (int s = 0; s < 100; ++s) {
        const Grid<std::uint8_t> old = model.cells();
        model.step();
        for (int i = 0; i < 30; ++i)
            for (int j = 0; j < 30; ++j) {
                const double u = reference.uniform();
                const bool burning_neighbour = old((i + 29) % 30, j) == fire || old((i + 1) % 30, j) == fire ||
                                               old(i, (j + 29) % 30) == fire || old(i, (j + 1) % 30) == fire;
                std::uint8_t expected = empty;
                if (old(i, j) == empty) expected = u < p.p ? tree : empty;
                if (old(i, j) == tree) expected = burning_neighbour || u < p.f ? fire : tree;
                REQUIRE(model.cells()(i, j) == expected);
            }
    }
    CHECK(model.steps() == 100);
}

TEST_CASE("forest fire state counts always sum to n squared", "[forest_fire]") {
    ForestFire model(lively(50), 3);
    bool saw_fire = false;
    for (int s = 0; s < 300; ++s) {
        model.step();
        REQUIRE(model.trees() + model.fires() + model.empties() == 2500);
        REQUIRE(model.trees() == count(model.cells(), tree));
        REQUIRE(model.fires() == count(model.cells(), fire));
        REQUIRE(model.empties() == count(model.cells(), empty));
        saw_fire = saw_fire || model.fires() > 0;
    }
    CHECK(saw_fire);
}

TEST_CASE("a burning cell is always empty the next step", "[forest_fire]") {
    ForestFire model(lively(40), 8);
    long burnt = 0;
    for (int s = 0; s < 300; ++s) {
        const Grid<std::uint8_t> old = model.cells();
        model.step();
        for (std::size_t c = 0; c < old.size(); ++c)
            if (old.cells()[c] == fire) {
                REQUIRE(model.cells().cells()[c] == empty);
                ++burnt;
            }
    }
    CHECK(burnt > 100);
}

TEST_CASE("with p and f zero and no fire the forest never changes", "[forest_fire]") {
    ForestFire model(ForestFireParams{40, 0.0, 0.0, 0.5}, 21);
    const Grid<std::uint8_t> start = model.cells();
    CHECK(model.trees() > 600);
    for (int s = 0; s < 50; ++s) model.step();
    CHECK(model.cells() == start);
}

TEST_CASE("a single fire in a full forest burns as a von Neumann diamond on the torus", "[forest_fire]") {
    // With p = f = 0 the fire is a breadth-first search from its start: at
    // step t exactly the cells at torus Manhattan distance t burn, nearer ones are empty.
    for (int n : {11, 10}) {
        Grid<std::uint8_t> forest(n, n, tree);
        const int ci = 4, cj = 6;
        forest(ci, cj) = fire;
        ForestFire model(ForestFireParams{n, 0.0, 0.0, 0.0}, forest, 1);
        auto torus = [n](int a, int b) {
            const int d = std::abs(a - b);
            return std::min(d, n - d);
        };
        const int farthest = 2 * (n / 2);
        for (int t = 1; t <= farthest + 1; ++t) {
            model.step();
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const int d = torus(i, ci) + torus(j, cj);
                    const std::uint8_t expected = d < t ? empty : d == t ? fire : tree;
                    INFO("n " << n << " step " << t << " cell " << i << " " << j);
                    REQUIRE(model.cells()(i, j) == expected);
                }
        }
        CHECK(model.empties() == long{n} * n);
    }
}

TEST_CASE("forest fire with the same seed gives the same state hash and a different seed differs", "[forest_fire]") {
    const ForestFireParams p{64, 0.01, 0.001, 0.01};
    ForestFire a(p, 7), b(p, 7), c(p, 8);
    for (int s = 0; s < 400; ++s) {
        a.step();
        b.step();
        c.step();
    }
    CHECK(fnv1a(a.cells()) == fnv1a(b.cells()));
    CHECK(a.cells() == b.cells());
    CHECK(fnv1a(a.cells()) != fnv1a(c.cells()));
}

TEST_CASE("forest fire rejects bad parameters and cells with messages naming them", "[forest_fire]") {
    auto message_of = [](ForestFireParams p) {
        try {
            p.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(message_of(ForestFireParams{}) == "accepted");
    CHECK(message_of(ForestFireParams{2, 0.01, 0.001, 0.01}) ==
          "n = 2 is not allowed: an integer from 3 to 8192");
    CHECK(message_of(ForestFireParams{200, -0.5, 0.001, 0.01}) ==
          "p = -0.5 is not allowed: a number from 0 to 1");
    CHECK(message_of(ForestFireParams{200, 0.01, 2, 0.01}) == "f = 2 is not allowed: a number from 0 to 1");
    CHECK(message_of(ForestFireParams{200, 0.01, 0.001, 1.5}) ==
          "initial_density = 1.5 is not allowed: a number from 0 to 1");
    Grid<std::uint8_t> bad(5, 5, tree);
    bad(2, 2) = 2;
    CHECK_THROWS_AS(ForestFire(ForestFireParams{5, 0.1, 0.1, 0.1}, bad, 1), std::invalid_argument);
    CHECK_THROWS_AS(ForestFire(ForestFireParams{6, 0.1, 0.1, 0.1}, Grid<std::uint8_t>(5, 5), 1),
                    std::invalid_argument);
}
