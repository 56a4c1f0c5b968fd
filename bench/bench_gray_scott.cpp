// Throughput of the fast Gray-Scott kernels (sim/gray_scott_kernels.hpp) in
// cell-updates per second: items_per_second = cells * steps. Args: n, threads.
//
// How close the float kernel comes to the machine's compute limit. A cell
// update is 33 flops (update_row): each laplacian 6 additions, 2
// multiplications, 1 addition and 1 subtraction (10, twice), the reaction 2
// multiplications, A's update 6 and B's 5; 23 additions or subtractions and
// 10 multiplications, none fusable (-ffp-contract=off: the bits must be the
// model's). The machine: 2 cores of an AMD EPYC of family 1Ah (Zen 5, lscpu:
// avx512f), four 512-bit FP pipes, two of them FMA; lscpu's 2096 MHz is the
// nominal TSC of the VM, a chain of dependent integer adds runs at 3.3 GHz.
// Peak single precision, FMA counted as 2: 2 pipes x 16 lanes x 2 = 64
// flops a cycle a core; without FMA the four pipes give at most 4 x 16 = 64
// single operations a cycle. So 2 x 3.3 GHz x 64 = 422 Gflop/s, or 422 / 33 =
// 12.8 G cell-updates/s for both cores. Measured here at n = 256 (the best
// of 30 short runs, as other jobs share the 2 cores): one thread 3.4-3.6
// G/s, 112-119 Gflop/s, 53-56% of a core's peak; two threads 4.7-5.4 G/s,
// 155-178 Gflop/s, 37-42% of both cores' (before AVX-512: 1.8 and 3.1 G/s).
// The arithmetic alone could come close: the AVX-512 row with every load
// made aligned (wrong results, a bound) does 5.7 G/s on one core with its
// rows in L1, 88% of the peak. The real row also shifts each row it loads
// (a valignd, on the FP pipes), loads the right neighbours unaligned (two
// cache lines each) and streams 16 bytes a cell from L2 (four 256^2 float
// fields, 1.2 MB, do not fit in L1): 4.6 G/s with its rows in L1, 3.5 in
// the kernel. Two threads lose ~3 us of each ~12 us step against twice one
// thread's rate: the barrier that ends every step, and the rows at the
// threads' borders, which pass from one core's cache to the other's.
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
    for (int n : {100, 128, 256, 1024, 4096})  // 128: a gs-atlas tile
        for (int threads : {1, 2}) b->Args({n, threads});
    b->UseRealTime();  // the work runs on OpenMP threads: wall time, not the main thread's CPU time
}

}  // namespace

BENCHMARK_TEMPLATE(gray_scott_kernel, float)->Apply(sizes);
BENCHMARK_TEMPLATE(gray_scott_kernel, double)->Apply(sizes);
