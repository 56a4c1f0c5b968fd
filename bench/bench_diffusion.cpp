// Diffusion throughput: cell updates per second against grid size.
#include <benchmark/benchmark.h>

#include "sim/diffusion.hpp"

static void diffusion_step(benchmark::State& state) {
    sim::DiffusionParams p;
    p.n = static_cast<int>(state.range(0));
    sim::Diffusion model(p);
    for (auto _ : state) model.step();
    state.SetItemsProcessed(state.iterations() * p.n * p.n);
}
BENCHMARK(diffusion_step)->Arg(9)->Arg(100)->Arg(1000);
