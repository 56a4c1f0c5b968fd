// Turtle throughput for the pl-lsys figures: segments drawn per second, the
// string streamed and read in one pass (nothing is built but the segments).
#include <benchmark/benchmark.h>

#include "sim/lsystem.hpp"
#include "sim/turtle.hpp"

// The article's club moss at depth 5, read both ways: state.range(0) = 1 is
// the article's recursion (9,330 segments), 0 the rewritten string (7,776).
static void lycopodium_depth_5(benchmark::State& state) {
    const bool article = state.range(0) == 1;
    state.SetLabel(article ? "article" : "rewrite");
    const sim::LSystem moss = sim::LSystem::parse("F", {"F -> FF+[+F-F]-[-F+F]"});
    std::size_t segments = 0;
    for (auto _ : state) {
        const auto drawn = sim::interpret_2d(moss, 5, sim::Turtle2Params{}, article);
        segments = drawn.size();
        benchmark::DoNotOptimize(drawn.data());
    }
    state.counters["segments"] = static_cast<double>(segments);
    state.SetItemsProcessed(state.iterations() * static_cast<long>(segments));  // segments per second
}
BENCHMARK(lycopodium_depth_5)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

// ABOP's apple tree (Fig 1.24 f) at depth 6: 6,048 segments.
static void abop_apple_depth_6(benchmark::State& state) {
    const sim::LSystem apple = sim::LSystem::parse("X", {"X -> F-[[X]+X]+F[+FX]-X", "F -> FF"});
    sim::Turtle2Params p;
    p.angle_degrees = 22.5;
    std::size_t segments = 0;
    for (auto _ : state) {
        const auto drawn = sim::interpret_2d(apple, 6, p, false);
        segments = drawn.size();
        benchmark::DoNotOptimize(drawn.data());
    }
    state.counters["segments"] = static_cast<double>(segments);
    state.SetItemsProcessed(state.iterations() * static_cast<long>(segments));
}
BENCHMARK(abop_apple_depth_6)->Unit(benchmark::kMicrosecond);
