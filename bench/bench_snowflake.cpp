// Growth of the sf87 snowflakes: a whole crystal per iteration, from the
// seed to step 1000 (radius 1000, the largest the figures could want).
#include <benchmark/benchmark.h>

#include "sim/snowflake.hpp"

// state.range(0) picks the rule: 0 is the odd-even rule 0101010 (Hex135,
// dendritic), 1 is Packard's Hex1, 0100000.
static void snowflake_1000_steps(benchmark::State& state) {
    const char* code = state.range(0) == 0 ? "0101010" : "0100000";
    state.SetLabel(code);
    sim::SnowflakeParams p;
    p.rule = sim::SnowflakeRule::parse(code);
    long cells = 0;
    for (auto _ : state) {
        sim::Snowflake flake(p);
        for (int t = 0; t < 1000; ++t) flake.step();
        cells = flake.ice_count();
        benchmark::DoNotOptimize(cells);
    }
    state.counters["cells"] = static_cast<double>(cells);  // ice cells at step 1000
    state.SetItemsProcessed(state.iterations() * cells);   // cells frozen per second
}
BENCHMARK(snowflake_1000_steps)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
