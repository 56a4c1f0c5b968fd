// The Newman-Ziff percolation threshold: samples per second at each lattice
// size, and the error of p_c against run time as the samples grow.
#include <benchmark/benchmark.h>

#include <cmath>

#include "sim/percolation_threshold.hpp"
#include "sim/random.hpp"

namespace {

constexpr double exact_p_c = 0.59274621;  // Newman & Ziff 2000

}  // namespace

// One sample: a random order of the L x L sites, occupied until the torus
// wraps both ways (about 0.6 L^2 sites). items/s is samples per second.
static void newman_ziff_sample(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0));
    sim::Random rng(1);
    for (auto _ : state) benchmark::DoNotOptimize(sim::wrapping_points(size, 1, rng));
    state.SetItemsProcessed(state.iterations());
    state.counters["sites"] = static_cast<double>(size) * size;
}
BENCHMARK(newman_ziff_sample)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMicrosecond);

// The estimate from the samples of one run, through the binomial convolution.
// It is a small part of a run: O(N) work per bisection step, not per sample.
static void newman_ziff_convolution(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0));
    sim::Random rng(2);
    const auto points = sim::wrapping_points(size, 1000, rng);
    for (auto _ : state) benchmark::DoNotOptimize(sim::threshold_from_wrapping(points, size));
}
BENCHMARK(newman_ziff_convolution)->Arg(64)->Arg(256)->Unit(benchmark::kMillisecond);

// Whole runs, error against time: |p_c - 0.59274621| and the reported
// standard error for L and sample count, one run per iteration (a fresh seed
// each time, so the error is a draw from its distribution, not a fixed value).
static void newman_ziff_estimate(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0)), samples = static_cast<int>(state.range(1));
    std::uint64_t seed = 100;
    double error = 0, standard_error = 0;
    for (auto _ : state) {
        sim::Random rng(seed++);
        const sim::ThresholdEstimate e = sim::newman_ziff_threshold(size, samples, rng);
        error = std::abs(e.p_c - exact_p_c);
        standard_error = e.standard_error;
    }
    state.counters["abs_error"] = error;
    state.counters["std_error"] = standard_error;
}
BENCHMARK(newman_ziff_estimate)
    ->Args({64, 1000})
    ->Args({64, 10000})
    ->Args({128, 1000})
    ->Args({128, 4000})
    ->Args({256, 1000})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
