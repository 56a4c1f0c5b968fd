// Throughput of the fast Gray-Scott kernels (sim/gray_scott_kernels.hpp) in
// cell-updates per second: items_per_second = cells * steps. Args: n, threads.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>

#include "kernel_throughput.hpp"
#include "sim/gray_scott.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/random.hpp"

namespace {

template <class Real>
void gray_scott_kernel(benchmark::State& state) {
    sim::GrayScottParams p;
    p.n = static_cast<int>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    sim::Random rng(17);
    const sim::GrayScott start(p, rng);
    sim::GrayScottKernel<Real> kernel(p, start.a(), start.b());
    bench::measure_steps(state, kernel, p.n, threads);
}

void sizes(benchmark::internal::Benchmark* b) {
    b->ArgNames({"n", "threads"});
    for (int n : {100, 256, 1024, 4096})
        for (int threads : {1, 2}) b->Args({n, threads});
    b->UseRealTime();  // the work runs on OpenMP threads: wall time, not the main thread's CPU time
}

}  // namespace

BENCHMARK_TEMPLATE(gray_scott_kernel, float)->Apply(sizes);
BENCHMARK_TEMPLATE(gray_scott_kernel, double)->Apply(sizes);
