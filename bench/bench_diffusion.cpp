// Diffusion throughput: cell updates per second against grid size, for the
// model (sim/diffusion.hpp) and the fast kernels (sim/diffusion_kernel.hpp).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>

#include "kernel_throughput.hpp"
#include "sim/diffusion.hpp"
#include "sim/diffusion_kernel.hpp"
#include "sim/random.hpp"

static void diffusion_step(benchmark::State& state) {
    sim::DiffusionParams p;
    p.n = static_cast<int>(state.range(0));
    sim::Diffusion model(p);
    for (auto _ : state) model.step();
    state.SetItemsProcessed(state.iterations() * p.n * p.n);
}
BENCHMARK(diffusion_step)->Arg(9)->Arg(100)->Arg(1000);

namespace {

// items_per_second = cells * steps. Args: n, threads.
template <class Real>
void diffusion_kernel(benchmark::State& state) {
    sim::DiffusionParams p;
    p.n = static_cast<int>(state.range(0));
    p.boundary = sim::Boundary::wrap;
    const int threads = static_cast<int>(state.range(1));
    sim::Random rng(17);
    sim::Grid<double> start(p.n, p.n);
    for (int i = 0; i < p.n; ++i)
        for (int j = 0; j < p.n; ++j) start(i, j) = rng.uniform();
    sim::DiffusionKernel<Real> kernel(p, start);
    bench::measure_steps(state, kernel, p.n, threads);
}

void sizes(benchmark::internal::Benchmark* b) {
    b->ArgNames({"n", "threads"});
    for (int n : {100, 256, 1024})
        for (int threads : {1, 2}) b->Args({n, threads});
    b->UseRealTime();  // the work runs on OpenMP threads: wall time, not the main thread's CPU time
}

}  // namespace

BENCHMARK_TEMPLATE(diffusion_kernel, float)->Apply(sizes);
BENCHMARK_TEMPLATE(diffusion_kernel, double)->Apply(sizes);
