// Throughput of formula models (sim/formula/rule.hpp) in cell-updates per
// second, beside the hand-written kernels (bench_gray_scott.cpp): Ready's
// own Gray-Scott formula (its File > New Pattern rule), compiled and fused
// into three chains (sim/formula/chain_kernels.hpp), in float and double. Args: n,
// threads.
#include <benchmark/benchmark.h>

#include "kernel_throughput.hpp"
#include "sim/formula/run.hpp"
#include "sim/gray_scott.hpp"
#include "sim/random.hpp"

namespace {

template <bool Double>
void gray_scott_formula(benchmark::State& state) {
    sim::GrayScottParams p;
    p.n = static_cast<int>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    sim::Random rng(17);
    const sim::GrayScott start(p, rng);
    sim::formula::Rule rule;
    rule.parameters = {{"timestep", 1.0}, {"D_a", 0.082}, {"D_b", 0.041}, {"K", 0.06}, {"F", 0.035}};
    rule.code = "delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\n"
                "delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;";
    rule.double_precision = Double;
    rule.ready_edges = false;  // a torus at any n
    sim::formula::Run run(rule, p.n, p.n, {start.a(), start.b()});
    bench::measure_steps(state, run, p.n, threads);
    state.counters["operations"] = run.operations();
}

void sizes(benchmark::internal::Benchmark* b) {
    b->ArgNames({"n", "threads"});
    for (int n : {128, 256, 1024})
        for (int threads : {1, 2}) b->Args({n, threads});
    b->UseRealTime();
}

}  // namespace

BENCHMARK_TEMPLATE(gray_scott_formula, false)->Apply(sizes);
BENCHMARK_TEMPLATE(gray_scott_formula, true)->Apply(sizes);
