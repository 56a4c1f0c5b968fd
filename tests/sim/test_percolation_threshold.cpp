#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <deque>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/percolation_threshold.hpp"
#include "sim/random.hpp"

using sim::WrapCriterion;
using sim::WrappingPoints;

namespace {

constexpr double exact_p_c = 0.59274621;  // Newman & Ziff 2000

std::uint32_t site(int size, int row, int col) { return static_cast<std::uint32_t>(row * size + col); }

// An independent wrapping check on a whole occupied lattice: breadth-first
// search gives each cluster unwrapped coordinates from its first site; a bond
// to a site already placed elsewhere winds round the torus.
WrappingPoints wraps_by_search(int size, const std::vector<bool>& occupied) {
    const int n = size * size;
    std::vector<int> ux(n, 0), uy(n, 0);
    std::vector<bool> seen(n, false);
    bool horizontal = false, vertical = false;
    for (int start = 0; start < n; ++start) {
        if (!occupied[start] || seen[start]) continue;
        seen[start] = true;
        ux[start] = start % size;
        uy[start] = start / size;
        std::deque<int> queue{start};
        while (!queue.empty()) {
            const int s = queue.front();
            queue.pop_front();
            const int ex[] = {1, -1, 0, 0}, ey[] = {0, 0, 1, -1};
            for (int d = 0; d < 4; ++d) {
                const int x = ((s % size + ex[d]) % size + size) % size, y = ((s / size + ey[d]) % size + size) % size;
                const int t = y * size + x;
                if (!occupied[t]) continue;
                const int tx = ux[s] + ex[d], ty = uy[s] + ey[d];
                if (!seen[t]) {
                    seen[t] = true;
                    ux[t] = tx;
                    uy[t] = ty;
                    queue.push_back(t);
                } else {
                    horizontal = horizontal || ux[t] != tx;
                    vertical = vertical || uy[t] != ty;
                }
            }
        }
    }
    return {horizontal ? 1u : 0u, vertical ? 1u : 0u};
}

}  // namespace

TEST_CASE("a full row wraps horizontally at exactly L sites in any order", "[threshold]") {
    for (int size : {2, 3, 4, 7, 16}) {
        std::vector<std::uint32_t> row;
        for (int col = 0; col < size; ++col) row.push_back(site(size, size / 2, col));
        WrappingPoints w = sim::wrapping_points_for_order(size, row);
        CHECK(w.horizontal == static_cast<std::uint32_t>(size));
        CHECK(w.vertical == 0);
        // Reversed, and with the middle last: the loop closes with the last site only.
        std::vector<std::uint32_t> reversed(row.rbegin(), row.rend());
        CHECK(sim::wrapping_points_for_order(size, reversed).horizontal == static_cast<std::uint32_t>(size));
        std::swap(row[static_cast<std::size_t>(size / 2)], row.back());
        CHECK(sim::wrapping_points_for_order(size, row).horizontal == static_cast<std::uint32_t>(size));
        row.pop_back();
        CHECK(sim::wrapping_points_for_order(size, row).horizontal == 0);
    }
}

TEST_CASE("a full column wraps vertically and a full row plus column wraps both ways", "[threshold]") {
    const int size = 5;
    std::vector<std::uint32_t> order;
    for (int row = 0; row < size; ++row) order.push_back(site(size, row, 3));
    WrappingPoints w = sim::wrapping_points_for_order(size, order);
    CHECK(w.vertical == 5);
    CHECK(w.horizontal == 0);
    for (int col = 0; col < size; ++col)
        if (col != 3) order.push_back(site(size, 1, col));
    w = sim::wrapping_points_for_order(size, order);
    CHECK(w.vertical == 5);
    CHECK(w.horizontal == 9);  // the row shares (1, 3) with the column: 4 more sites
}

TEST_CASE("a diagonal staircase wraps both ways at once when its last step closes it", "[threshold]") {
    const int size = 4;
    // (0,0) (0,1) (1,1) (1,2) (2,2) (2,3) (3,3) then (3,0), which touches (3,3)
    // across the side and (0,0) across the bottom: winding (1, 1).
    const std::vector<std::uint32_t> order{site(size, 0, 0), site(size, 0, 1), site(size, 1, 1), site(size, 1, 2),
                                           site(size, 2, 2), site(size, 2, 3), site(size, 3, 3), site(size, 3, 0)};
    const WrappingPoints w = sim::wrapping_points_for_order(size, order);
    CHECK(w.horizontal == 8);
    CHECK(w.vertical == 8);
    const std::vector<std::uint32_t> open(order.begin(), order.end() - 1);
    const WrappingPoints before = sim::wrapping_points_for_order(size, open);
    CHECK(before.horizontal == 0);
    CHECK(before.vertical == 0);
}

TEST_CASE("a 1 x 1 torus wraps both ways with its only site", "[threshold]") {
    const std::vector<std::uint32_t> order{0};
    const WrappingPoints w = sim::wrapping_points_for_order(1, order);
    CHECK(w.horizontal == 1);
    CHECK(w.vertical == 1);
}

TEST_CASE("union-find wrapping agrees with a breadth-first search after every site", "[threshold]") {
    for (int size : {2, 3, 5, 8}) {
        const int n = size * size;
        for (std::uint64_t seed = 1; seed <= 30; ++seed) {
            sim::Random rng(seed);
            std::vector<std::uint32_t> order(static_cast<std::size_t>(n));
            std::iota(order.begin(), order.end(), 0u);
            for (int i = n - 1; i > 0; --i)
                std::swap(order[static_cast<std::size_t>(i)],
                          order[rng.below(static_cast<std::uint64_t>(i) + 1)]);
            const WrappingPoints w = sim::wrapping_points_for_order(size, order);
            std::vector<bool> occupied(static_cast<std::size_t>(n), false);
            std::uint32_t first_h = 0, first_v = 0;
            for (int k = 0; k < n; ++k) {
                occupied[order[static_cast<std::size_t>(k)]] = true;
                const WrappingPoints now = wraps_by_search(size, occupied);
                if (now.horizontal && first_h == 0) first_h = static_cast<std::uint32_t>(k + 1);
                if (now.vertical && first_v == 0) first_v = static_cast<std::uint32_t>(k + 1);
            }
            INFO("size " << size << " seed " << seed);
            CHECK(w.horizontal == first_h);
            CHECK(w.vertical == first_v);
        }
    }
}

TEST_CASE("wrapping occupation is the first wrap either way and lies between L and N", "[threshold]") {
    sim::Random a(11), b(11);
    const std::vector<std::uint32_t> first = sim::wrapping_occupation(16, 200, a);
    const std::vector<WrappingPoints> points = sim::wrapping_points(16, 200, b);
    REQUIRE(first.size() == 200);
    REQUIRE(points.size() == 200);
    double mean = 0;
    for (std::size_t s = 0; s < first.size(); ++s) {
        CHECK(first[s] == std::min(points[s].horizontal, points[s].vertical));
        CHECK(points[s].horizontal >= 16);
        CHECK(points[s].vertical >= 16);
        CHECK(points[s].horizontal <= 256);
        CHECK(points[s].vertical <= 256);
        mean += first[s] / 256.0 / 200.0;
    }
    CHECK(mean > 0.5);  // the first wrap comes a little below p_c on small tori
    CHECK(mean < 0.65);
}

TEST_CASE("wrapping probability by convolution rises from 0 to 1 through its value at p_c", "[threshold]") {
    sim::Random rng(3);
    const std::vector<WrappingPoints> points = sim::wrapping_points(32, 300, rng);
    for (WrapCriterion c :
         {WrapCriterion::one_direction, WrapCriterion::either_direction, WrapCriterion::both_directions}) {
        double last = -1;
        for (double p = 0.0; p <= 1.0; p += 0.05) {
            const double r = sim::wrapping_probability(points, 32, c, p);
            CHECK(r >= last - 1e-12);
            last = r;
        }
        CHECK(sim::wrapping_probability(points, 32, c, 0.0) == 0.0);
        CHECK(sim::wrapping_probability(points, 32, c, 1.0) == Approx(1.0));
        CHECK(sim::wrapping_probability(points, 32, c, 0.5) < 0.1);
        CHECK(sim::wrapping_probability(points, 32, c, 0.7) > 0.9);
        const sim::ThresholdEstimate e = sim::threshold_from_wrapping(points, 32, c);
        CHECK(sim::wrapping_probability(points, 32, c, e.p_c) ==
              Approx(sim::wrapping_probability_at_threshold(c)).margin(1e-9));
    }
}

TEST_CASE("the threshold at L 32 from 400 samples is within 0.01 of 0.59274621", "[threshold]") {
    sim::Random rng(2000);
    const sim::ThresholdEstimate e = sim::newman_ziff_threshold(32, 400, rng);
    INFO("p_c = " << e.p_c << " +- " << e.standard_error);
    CHECK(std::abs(e.p_c - exact_p_c) < 0.01);
    CHECK(e.standard_error > 0);
    CHECK(e.standard_error < 0.005);
    CHECK(std::abs(e.p_c - exact_p_c) < 5 * e.standard_error);  // the error bar is honest
    CHECK(e.samples == 400);
    CHECK(e.size == 32);
    for (WrapCriterion c : {WrapCriterion::either_direction, WrapCriterion::both_directions}) {
        sim::Random again(2000);
        const sim::ThresholdEstimate other = sim::newman_ziff_threshold(32, 400, again, c);
        CHECK(std::abs(other.p_c - exact_p_c) < 0.01);
    }
}

TEST_CASE("the same seed gives the same threshold and a different seed another", "[threshold]") {
    sim::Random a(77), b(77), c(78);
    const sim::ThresholdEstimate ea = sim::newman_ziff_threshold(24, 100, a);
    const sim::ThresholdEstimate eb = sim::newman_ziff_threshold(24, 100, b);
    const sim::ThresholdEstimate ec = sim::newman_ziff_threshold(24, 100, c);
    CHECK(ea.p_c == eb.p_c);
    CHECK(ea.standard_error == eb.standard_error);
    CHECK(a.next() == b.next());  // and the same number of draws
    CHECK(ea.p_c != ec.p_c);
}

TEST_CASE("threshold rejects bad sizes sample counts and orders with messages naming them", "[threshold]") {
    auto message_of = [](auto call) {
        try {
            call();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    sim::Random rng(1);
    CHECK(message_of([&] { sim::newman_ziff_threshold(0, 10, rng); }) ==
          "size = 0 is not allowed: an integer from 1 to 4096");
    CHECK(message_of([&] { sim::newman_ziff_threshold(5000, 10, rng); }) ==
          "size = 5000 is not allowed: an integer from 1 to 4096");
    CHECK(message_of([&] { sim::newman_ziff_threshold(8, 0, rng); }) ==
          "samples = 0 is not allowed: an integer from 1 to 100000000");
    CHECK(message_of([&] { sim::wrapping_occupation(8, -3, rng); }) ==
          "samples = -3 is not allowed: an integer from 1 to 100000000");
    const std::vector<std::uint32_t> outside{0, 16};
    CHECK(message_of([&] { sim::wrapping_points_for_order(4, outside); }) ==
          "site = 16 is not allowed: sites must be below 16");
    const std::vector<std::uint32_t> twice{3, 5, 3};
    CHECK(message_of([&] { sim::wrapping_points_for_order(4, twice); }) ==
          "site = 3 is not allowed: it is already occupied");
    CHECK(message_of([&] { sim::threshold_from_wrapping({}, 4); }) ==
          "points is empty: at least one sample is needed");
    CHECK(message_of([&] { sim::wrapping_probability({{5, 6}}, 4, WrapCriterion::one_direction, 1.5); }) ==
          "p = 1.5 is not allowed: a number from 0 to 1");
}

TEST_CASE("wrapping probability at many p gives the one-p call's bits at each", "[threshold]") {
    sim::Random rng(5);
    const std::vector<WrappingPoints> points = sim::wrapping_points(24, 200, rng);
    const std::vector<double> ps{0.0, 0.3, 0.55, 0.5927, 0.61, 0.9, 1.0};
    for (WrapCriterion c :
         {WrapCriterion::one_direction, WrapCriterion::either_direction, WrapCriterion::both_directions}) {
        const std::vector<double> curve = sim::wrapping_probability(points, 24, c, ps);
        REQUIRE(curve.size() == ps.size());
        for (std::size_t i = 0; i < ps.size(); ++i) CHECK(curve[i] == sim::wrapping_probability(points, 24, c, ps[i]));
    }
    CHECK(sim::wrapping_probability(points, 24, WrapCriterion::one_direction, std::vector<double>{}).empty());
    CHECK_THROWS_WITH(sim::wrapping_probability(points, 24, WrapCriterion::one_direction, std::vector<double>{0.5, -1}),
                      "p = -1 is not allowed: a number from 0 to 1");
}

TEST_CASE("two sizes' wrapping curves cross where they are equal and nowhere outside their range", "[threshold]") {
    sim::Random a(8), b(9);
    const std::vector<WrappingPoints> small = sim::wrapping_points(16, 2000, a);
    const std::vector<WrappingPoints> large = sim::wrapping_points(32, 2000, b);
    const WrapCriterion c = WrapCriterion::one_direction;
    const std::optional<double> p = sim::wrapping_crossing(small, 16, large, 32, c, 0.5, 0.7);
    REQUIRE(p.has_value());
    INFO("crossing at " << *p);
    CHECK(std::abs(*p - exact_p_c) < 0.01);
    CHECK(sim::wrapping_probability(large, 32, c, *p) ==
          Approx(sim::wrapping_probability(small, 16, c, *p)).margin(1e-9));
    // The larger lattice's curve is the steeper: below the crossing it is under the smaller's.
    CHECK(sim::wrapping_probability(large, 32, c, *p - 0.02) < sim::wrapping_probability(small, 16, c, *p - 0.02));
    CHECK(sim::wrapping_probability(large, 32, c, *p + 0.02) > sim::wrapping_probability(small, 16, c, *p + 0.02));
    // Either order of the two sets finds the same crossing.
    const std::optional<double> swapped = sim::wrapping_crossing(large, 32, small, 16, c, 0.5, 0.7);
    REQUIRE(swapped.has_value());
    CHECK(*swapped == Approx(*p).margin(1e-10));
    // Far below p_c both curves are 0 to rounding and far above both 1: no change of sign there.
    CHECK_FALSE(sim::wrapping_crossing(small, 16, large, 32, c, 0.05, 0.1).has_value());
    CHECK_FALSE(sim::wrapping_crossing(small, 16, small, 16, c, 0.5, 0.7).has_value());
}

TEST_CASE("the extrapolation in L^(-11/4) recovers an exact line and weighs by the error bars", "[threshold]") {
    auto x = [](int size) { return std::pow(static_cast<double>(size), -11.0 / 4.0); };
    std::vector<sim::ThresholdEstimate> line;
    for (int size : {16, 32, 64, 128}) line.push_back({0.5927 + 3.0 * x(size), 1e-4 * size / 16.0, 1000, size});
    const sim::ThresholdExtrapolation fit = sim::extrapolate_threshold(line);
    CHECK(fit.p_c == Approx(0.5927).epsilon(1e-12));
    CHECK(fit.slope == Approx(3.0).epsilon(1e-6));
    CHECK(fit.chi_squared == Approx(0.0).margin(1e-12));
    CHECK(fit.degrees_of_freedom == 2);
    // Two points: the line through them, with the errors of the two-point formulas.
    const std::vector<sim::ThresholdEstimate> two{{0.60, 0.002, 100, 2}, {0.59, 0.001, 100, 4}};
    const sim::ThresholdExtrapolation through = sim::extrapolate_threshold(two);
    const double x1 = x(2), x2 = x(4);
    const double slope = (0.60 - 0.59) / (x1 - x2), intercept = 0.59 - slope * x2;
    CHECK(through.p_c == Approx(intercept).epsilon(1e-12));
    CHECK(through.slope == Approx(slope).epsilon(1e-12));
    // The intercept's variance: each estimate's weight in it, squared, times its variance.
    const double w1 = -x2 / (x1 - x2), w2 = x1 / (x1 - x2);
    CHECK(through.standard_error == Approx(std::sqrt(w1 * w1 * 0.002 * 0.002 + w2 * w2 * 0.001 * 0.001)).epsilon(1e-9));
    CHECK(through.degrees_of_freedom == 0);
    // Bad input is refused with a message naming it.
    CHECK_THROWS_WITH(sim::extrapolate_threshold(std::vector<sim::ThresholdEstimate>{two[0]}),
                      "estimates = 1 is not allowed: two lattice sizes at least, to fit a line");
    CHECK_THROWS_WITH(sim::extrapolate_threshold(std::vector<sim::ThresholdEstimate>{two[0], two[0]}),
                      "size = 2 is not allowed: each lattice size once");
    std::vector<sim::ThresholdEstimate> flat = two;
    flat[1].standard_error = 0;
    CHECK_THROWS_WITH(sim::extrapolate_threshold(flat),
                      "standard_error = 0 is not allowed: a finite number above 0 (at L = 4)");
}
