#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <utility>
#include <string>
#include <vector>

#include "sim/percolation.hpp"
#include "sim/random.hpp"

using sim::Grid;
using sim::Percolation;
using sim::PercolationParams;
using sim::PercolationStop;

namespace {

constexpr std::uint8_t blocked = 0, porous = 1, wet = 5;

// Breadth-first search from the top row through cells that are not blocked:
// distance in steps from the top row, or -1 where water never gets.
Grid<int> flood_fill_distance(const Grid<std::uint8_t>& start) {
    const int rows = start.rows(), cols = start.cols();
    Grid<int> distance(rows, cols, -1);
    std::deque<std::pair<int, int>> queue;
    for (int j = 0; j < cols; ++j)
        if (start(0, j) != blocked) {
            distance(0, j) = 0;
            queue.emplace_back(0, j);
        }
    while (!queue.empty()) {
        const auto [i, j] = queue.front();
        queue.pop_front();
        const int di[] = {-1, 1, 0, 0}, dj[] = {0, 0, -1, 1};
        for (int d = 0; d < 4; ++d) {
            const int ni = i + di[d], nj = j + dj[d];
            if (ni < 0 || ni >= rows || nj < 0 || nj >= cols) continue;
            if (start(ni, nj) == blocked || distance(ni, nj) >= 0) continue;
            distance(ni, nj) = distance(i, j) + 1;
            queue.emplace_back(ni, nj);
        }
    }
    return distance;
}

// The book's step over the whole grid: c = correlate2d(a, cross, 'same')
// with zero fill, then a[(a == 1) & (c >= 5)] = 5, all from the old a.
Grid<std::uint8_t> book_step(const Grid<std::uint8_t>& a) {
    Grid<std::uint8_t> next = a;
    auto at = [&](int i, int j) { return i < 0 || i >= a.rows() || j < 0 || j >= a.cols() ? 0 : int{a(i, j)}; };
    for (int i = 0; i < a.rows(); ++i)
        for (int j = 0; j < a.cols(); ++j) {
            const int c = at(i - 1, j) + at(i + 1, j) + at(i, j - 1) + at(i, j + 1);
            if (a(i, j) == porous && c >= 5) next(i, j) = wet;
        }
    return next;
}

}  // namespace

TEST_CASE("percolation draws one uniform per cell and then wets the whole top row", "[percolation]") {
    sim::Random rng(5), reference(5);
    const Percolation model(PercolationParams{10, 0.7}, rng);
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            const std::uint8_t drawn = reference.uniform() < 0.7 ? porous : blocked;
            REQUIRE(model.cells()(i, j) == (i == 0 ? wet : drawn));
        }
    CHECK(rng.next() == reference.next());  // the top row drew too: exactly n * n draws
    CHECK(model.wet_count() == 10);
    CHECK_FALSE(model.bottom_row_wet());
    CHECK(model.steps() == 0);
}

TEST_CASE("percolation's front update equals the book's whole-grid rule after every step", "[percolation]") {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        sim::Random rng(seed);
        Percolation model(PercolationParams{40, 0.45 + 0.01 * static_cast<double>(seed)}, rng);
        Grid<std::uint8_t> book = model.cells();
        for (;;) {
            const Grid<std::uint8_t> before = book;
            book = book_step(book);
            long changed = 0;
            for (std::size_t c = 0; c < book.size(); ++c) changed += book.cells()[c] != before.cells()[c];
            REQUIRE(model.step() == changed);
            REQUIRE(model.cells() == book);
            if (changed == 0) break;
        }
    }
}

TEST_CASE("wet cells at the fixed point are exactly the flood fill from the top row and steps equal its layers",
          "[percolation]") {
    int percolating = 0;
    for (std::uint64_t seed = 100; seed < 160; ++seed) {
        sim::Random rng(seed);
        const double q = 0.5 + 0.005 * static_cast<double>(seed - 100);  // 0.5 .. 0.8
        Percolation model(PercolationParams{60, q}, rng);
        const Grid<int> distance = flood_fill_distance(model.cells());
        int layers = 0;
        long reachable = 0;
        for (int d : distance.cells()) {
            layers = std::max(layers, d);
            reachable += d >= 0;
        }
        // Step t wets exactly the cells at distance t.
        for (int t = 1; t <= layers; ++t) {
            model.step();
            for (int i = 0; i < 60; ++i)
                for (int j = 0; j < 60; ++j) {
                    const int d = distance(i, j);
                    REQUIRE((model.cells()(i, j) == wet) == (d >= 0 && d <= t));
                }
        }
        const sim::PercolationRun run = sim::run_to_fixed_point(model);
        CHECK(run.steps == 1);  // the layers are used up: the next step wets nothing
        CHECK(run.reason == PercolationStop::fixed_point);
        CHECK(model.steps() == layers + 1);
        CHECK(model.wet_count() == reachable);
        bool bottom = false;
        for (int j = 0; j < 60; ++j) bottom = bottom || distance(59, j) >= 0;
        CHECK(run.percolates == bottom);
        CHECK(model.bottom_row_wet() == bottom);
        percolating += bottom;
    }
    CHECK(percolating > 5);  // both outcomes were exercised
    CHECK(percolating < 55);
}

TEST_CASE("test_perc stops at the first step that wets the bottom row or wets nothing", "[percolation]") {
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        sim::Random rng(seed), same(seed);
        Percolation book(PercolationParams{30, 0.6}, rng), full(PercolationParams{30, 0.6}, same);
        const sim::PercolationRun run = sim::run_to_bottom_or_fixed_point(book);
        const Grid<int> distance = flood_fill_distance(full.cells());
        int first_bottom = -1, layers = 0;  // layer that reaches the bottom row, and the deepest layer
        for (int j = 0; j < 30; ++j) {
            const int d = distance(29, j);
            if (d >= 0 && (first_bottom < 0 || d < first_bottom)) first_bottom = d;
        }
        for (int d : distance.cells()) layers = std::max(layers, d);
        if (first_bottom >= 0) {
            CHECK(run.percolates);
            CHECK(run.reason == PercolationStop::bottom_row_wet);
            CHECK(run.steps == first_bottom);
        } else {
            CHECK_FALSE(run.percolates);
            CHECK(run.reason == PercolationStop::fixed_point);
            CHECK(run.steps == layers + 1);
        }
        CHECK(book.steps() == run.steps);
        const sim::PercolationRun to_end = sim::run_to_fixed_point(full);
        CHECK(to_end.percolates == run.percolates);
        CHECK(to_end.steps == layers + 1);
    }
}

TEST_CASE("percolation with q 1 percolates in n minus 1 steps", "[percolation]") {
    for (int n : {1, 2, 10, 257}) {
        sim::Random rng(9);
        Percolation model(PercolationParams{n, 1.0}, rng);
        const sim::PercolationRun run = sim::run_to_bottom_or_fixed_point(model);
        CHECK(run.percolates);
        CHECK(run.reason == PercolationStop::bottom_row_wet);
        // test_perc always takes one step, even when the top row is the bottom row.
        CHECK(run.steps == std::max(n - 1, 1));
        Percolation again(PercolationParams{n, 1.0}, rng);
        const sim::PercolationRun to_end = sim::run_to_fixed_point(again);
        CHECK(to_end.percolates);
        CHECK(to_end.steps == n);  // n - 1 rows to wet, then a step that wets nothing
        CHECK(again.wet_count() == long{n} * n);
    }
}

TEST_CASE("percolation with q 0 never percolates", "[percolation]") {
    sim::Random rng(4);
    Percolation model(PercolationParams{50, 0.0}, rng);
    const sim::PercolationRun run = sim::run_to_bottom_or_fixed_point(model);
    CHECK_FALSE(run.percolates);
    CHECK(run.reason == PercolationStop::fixed_point);
    CHECK(run.steps == 1);
    CHECK(model.wet_count() == 50);
}

TEST_CASE("percolation probability at n 100 rises from near 0 at q 0.55 to near 1 at q 0.65", "[percolation]") {
    // The book: about 0 at 0.55, 0.7 at 0.60, 1 at 0.65 (p_c = 0.5927).
    // One generator for all trials, as the book's global np.random.
    sim::Random rng(2024);
    auto estimate = [&](double q) {
        int yes = 0;
        for (int t = 0; t < 100; ++t) {
            Percolation model(PercolationParams{100, q}, rng);
            yes += sim::run_to_bottom_or_fixed_point(model).percolates;
        }
        return yes / 100.0;
    };
    const double p55 = estimate(0.55), p60 = estimate(0.60), p65 = estimate(0.65);
    INFO("P(0.55) = " << p55 << " P(0.60) = " << p60 << " P(0.65) = " << p65);
    CHECK(p55 < 0.2);
    CHECK(p60 > 0.3);
    CHECK(p60 < 0.95);
    CHECK(p65 > 0.8);
}

TEST_CASE("percolation rejects bad parameters and cells with messages naming them", "[percolation]") {
    auto message_of = [](PercolationParams p) {
        try {
            p.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(message_of(PercolationParams{}) == "accepted");
    CHECK(message_of(PercolationParams{0, 0.5}) == "n = 0 is not allowed: an integer from 1 to 8192");
    CHECK(message_of(PercolationParams{10, 1.5}) == "q = 1.5 is not allowed: a number from 0 to 1");
    Grid<std::uint8_t> bad(3, 3, porous);
    bad(1, 1) = 2;
    CHECK_THROWS_AS(Percolation(bad), std::invalid_argument);
    CHECK_THROWS_AS(Percolation(Grid<std::uint8_t>()), std::invalid_argument);
}
