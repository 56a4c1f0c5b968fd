#pragma once
// Cell-updates per second of a stencil kernel (sim/*_kernel*.hpp) for
// Google Benchmark: items_per_second = cells * steps.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>

namespace bench {

// About 4 M cell-updates per iteration (at least one step): small grids run
// several steps in one parallel region, as the figures' long runs do.
template <class Kernel>
void measure_steps(benchmark::State& state, Kernel& kernel, int n, int threads) {
    const std::int64_t cells = static_cast<std::int64_t>(n) * n;
    const int steps = static_cast<int>(std::max<std::int64_t>(1, (std::int64_t{1} << 22) / cells));
    kernel.step(steps, threads);  // warm the caches and the thread team
    for (auto _ : state) kernel.step(steps, threads);
    state.SetItemsProcessed(state.iterations() * steps * cells);
    state.counters["steps_per_iter"] = steps;
}

}  // namespace bench
