#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <set>

#include "sim/random.hpp"

// Expected values: SplitMix64 and xoshiro256** reference outputs. The
// seed-0 SplitMix64 words are the published test vector of Vigna's
// splitmix64.c; the state {1,2,3,4} outputs follow from the algorithm by hand
// (first: rotl(2*5, 7)*9 = 11520); the seeded values were computed by an
// independent Python implementation of the two algorithms.

TEST_CASE("SplitMix64 matches its reference outputs for seed 0", "[random]") {
    sim::SplitMix64 g(0);
    CHECK(g.next() == 0xe220a8397b1dcdafULL);
    CHECK(g.next() == 0x6e789e6aa1b965f4ULL);
    CHECK(g.next() == 0x06c45d188009454fULL);
}

TEST_CASE("xoshiro256** from state {1,2,3,4} gives the reference sequence", "[random]") {
    auto g = sim::Random::from_state({1, 2, 3, 4});
    CHECK(g.next() == 11520ULL);
    CHECK(g.next() == 0ULL);
    CHECK(g.next() == 1509978240ULL);
    CHECK(g.next() == 1215971899390074240ULL);
}

TEST_CASE("a seeded generator reproduces fixed known outputs", "[random]") {
    sim::Random g(42);
    CHECK(g.next() == 0x15780b2e0c2ec716ULL);
    CHECK(g.next() == 0x6104d9866d113a7eULL);
    CHECK(g.next() == 0xae17533239e499a1ULL);

    sim::Random u(42);
    CHECK(u.uniform() == 0.08386297105988216);  // exact: (x >> 11) * 2^-53 is exact in double
    CHECK(u.uniform() == 0.3789802506626686);
    CHECK(u.uniform() == 0.6800434110281394);

    sim::Random b(7);
    const std::uint64_t expected[] = {4, 4, 8, 4, 4, 1, 6, 6, 8, 9};
    for (std::uint64_t e : expected) CHECK(b.below(10) == e);
}

TEST_CASE("same seed gives same bits and different seeds differ", "[random]") {
    sim::Random a(2024), b(2024), c(2025);
    bool all_same_as_c = true;
    for (int i = 0; i < 1000; ++i) {
        const auto x = a.next();
        REQUIRE(x == b.next());
        all_same_as_c = all_same_as_c && x == c.next();
    }
    CHECK_FALSE(all_same_as_c);
}

TEST_CASE("uniform draws stay in the unit interval with the right mean", "[random]") {
    sim::Random g(1);
    double sum = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const double x = g.uniform();
        REQUIRE(x >= 0.0);
        REQUIRE(x < 1.0);
        sum += x;
    }
    // Mean of U(0,1) is 1/2 with standard error 1/sqrt(12 n) = 0.00065.
    CHECK(sum / n == Approx(0.5).margin(0.003));
}

TEST_CASE("below(n) covers 0..n-1 and nothing else", "[random]") {
    sim::Random g(3);
    std::set<std::uint64_t> seen;
    for (int i = 0; i < 1000; ++i) {
        const auto x = g.below(6);
        REQUIRE(x < 6);
        seen.insert(x);
    }
    CHECK(seen.size() == 6);
    CHECK(g.below(1) == 0);
}

TEST_CASE("an all-zero state is refused", "[random]") {
    CHECK_THROWS_AS(sim::Random::from_state({0, 0, 0, 0}), std::invalid_argument);
}

TEST_CASE("an item's stream depends on seed and item only", "[random]") {
    // The definition: SplitMix64 words from the counter that mixes both keys.
    const std::uint64_t seed = 17, item = 42;
    sim::SplitMix64 mix(sim::SplitMix64(seed).next() + sim::SplitMix64(~item).next());
    std::array<std::uint64_t, 4> state{};
    for (auto& word : state) word = mix.next();
    CHECK(sim::Random::for_item(seed, item).state() == state);
    CHECK(sim::Random::for_item(seed, item).next() == sim::Random::for_item(seed, item).next());
    CHECK(sim::Random::for_item(seed, item).next() != sim::Random::for_item(seed, item + 1).next());
    CHECK(sim::Random::for_item(seed, item).next() != sim::Random::for_item(seed + 1, item).next());
    // Item 0 of seed s is not the plain stream of s.
    CHECK(sim::Random::for_item(seed, 0).next() != sim::Random(seed).next());
    // The first draws of 4000 items are uniform: their mean is 1/2 within 5 standard errors.
    double sum = 0;
    for (std::uint64_t i = 0; i < 4000; ++i) sum += sim::Random::for_item(seed, i).uniform();
    CHECK(std::abs(sum / 4000 - 0.5) < 5 * std::sqrt(1.0 / 12 / 4000));
}
