// Throughput of the chapter 7 models at the sizes the figures use.
#include <benchmark/benchmark.h>

#include "sim/cell1d.hpp"
#include "sim/forest_fire.hpp"
#include "sim/gray_scott.hpp"
#include "sim/percolation.hpp"
#include "sim/random.hpp"

// One Gray-Scott step; the figures run 7000 of them at n = 100.
static void gray_scott_step(benchmark::State& state) {
    sim::GrayScottParams p;
    p.n = static_cast<int>(state.range(0));
    sim::Random rng(17);
    sim::GrayScott model(p, rng);
    for (auto _ : state) model.step();
    state.SetItemsProcessed(state.iterations() * p.n * p.n);
}
BENCHMARK(gray_scott_step)->Arg(100)->Arg(256);

// One percolation trial as tc7-phase runs it: draw the grid, then step to the
// fixed point (past the bottom row, so every trial does the whole cluster).
static void percolation_to_fixed_point(benchmark::State& state) {
    const sim::PercolationParams p{static_cast<int>(state.range(0)), 0.6};
    sim::Random rng(1);
    for (auto _ : state) {
        sim::Percolation model(p, rng);
        benchmark::DoNotOptimize(sim::run_to_fixed_point(model));
    }
    state.SetItemsProcessed(state.iterations() * p.n * p.n);
}
BENCHMARK(percolation_to_fixed_point)->Arg(100)->Arg(300)->Unit(benchmark::kMicrosecond);

// One forest-fire step at the exercise's n = 200 (after 100 steps to let fires start).
static void forest_fire_step(benchmark::State& state) {
    sim::ForestFire model(sim::ForestFireParams{}, 1);
    for (int s = 0; s < 100; ++s) model.step();
    for (auto _ : state) model.step();
    state.SetItemsProcessed(state.iterations() * 200 * 200);
}
BENCHMARK(forest_fire_step);

// The book's count_cells(18, 500): 500 rows of 1001 cells.
static void count_cells_rule_18(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(sim::count_cells(18, 500, sim::Boundary::zero));
}
BENCHMARK(count_cells_rule_18)->Unit(benchmark::kMicrosecond);
