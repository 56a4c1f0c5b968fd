// Ballistic deposition at the bd figures' sizes: a whole deposit of L^2
// particles per iteration (bd-500 runs L = 500), with the store of every
// particle's cell that the drawing needs, and without it as the roughness
// curves run. Counters: particles per second, and bytes per particle of the
// heights plus the store (capacity, from sizeof of the entries).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "sim/deposition.hpp"

static void deposition_l_squared(benchmark::State& state) {
    const int width = static_cast<int>(state.range(0));
    const bool record = state.range(1) != 0;
    const std::uint64_t particles = static_cast<std::uint64_t>(width) * width;
    state.SetLabel(record ? "recorded" : "heights only");
    double bytes = 0;
    for (auto _ : state) {
        sim::Deposition model(sim::DepositionParams{width, particles, record}, 1);
        model.drop(particles);
        benchmark::DoNotOptimize(model.heights().data());
        bytes = static_cast<double>(model.memory_bytes());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(particles));  // particles per second
    state.counters["bytes_per_particle"] = bytes / static_cast<double>(particles);
    state.counters["MB"] = bytes / 1e6;
}
BENCHMARK(deposition_l_squared)
    ->Args({500, 1})
    ->Args({500, 0})
    ->Args({2000, 1})
    ->Args({2000, 0})
    ->Unit(benchmark::kMillisecond);

// Copying the deposit out for drawing: particles() in arrival order.
static void deposition_particles(benchmark::State& state) {
    const int width = static_cast<int>(state.range(0));
    const std::uint64_t particles = static_cast<std::uint64_t>(width) * width;
    sim::Deposition model(sim::DepositionParams{width, particles, true}, 1);
    model.drop(particles);
    for (auto _ : state) benchmark::DoNotOptimize(model.particles().data());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(particles));
}
BENCHMARK(deposition_particles)->Arg(500)->Arg(2000)->Unit(benchmark::kMillisecond);
