// A 2-D formula run's steps in blocks (sim/formula/run.cpp's
// blocked_steps) against the same run one step at a time: the same bits
// on any number of threads, with wrapped, clamped and Ready's edges and
// stencils that reach one and two rows, and the same failure, step, cell
// and state where a step fails inside a block.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "grid_bits.hpp"
#include "sim/formula/run.hpp"
#include "sim/random.hpp"

using sim::Grid;
using namespace sim::formula;

namespace {

// Each chemical's cells after `steps` steps on `threads` threads, one step at a time or in blocks.
std::vector<Grid<double>> after(const Rule& rule, int width, int height, const std::vector<Grid<double>>& start,
                                int steps, int threads, bool blocks, int* block_steps = nullptr) {
    use_temporal_blocking(blocks);
    Run run(rule, width, height, start);
    run.step(steps, threads);
    use_temporal_blocking(true);
    if (block_steps) *block_steps = run.block_steps();
    std::vector<Grid<double>> out;
    for (int c = 0; c < rule.chemicals; ++c) out.push_back(run.chemical(c));
    return out;
}

std::vector<Grid<double>> noise(int width, int height, int chemicals) {
    sim::Random rng(7);
    std::vector<Grid<double>> start;
    for (int c = 0; c < chemicals; ++c) {
        Grid<double> g(height, width);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) g(y, x) = c == 0 ? 1.0 - 0.5 * rng.uniform() : 0.25 * rng.uniform();
        start.push_back(g);
    }
    return start;
}

}  // namespace

TEST_CASE("a 2-D run in blocks of steps gives the bits of one step at a time", "[formula][blocks]") {
    Rule gs;
    gs.chemicals = 2;
    gs.parameters = {{"timestep", 1.0}, {"D_a", 0.2}, {"D_b", 0.1}, {"F", 0.037}, {"K", 0.06}};
    gs.code = "delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\n"
              "delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;";
    gs.fused_multiply_add = true;
    struct Case {
        const char* name;
        int width, height;
        Accuracy accuracy;
        bool wrap, ready_edges, double_precision;
    };
    const Case cases[] = {
        {"Ready's wrap, float", 64, 128, Accuracy::medium, true, true, false},
        {"a true torus of 100 rows, float", 72, 100, Accuracy::medium, true, false, false},
        {"clamped, double, 5 x 5 stencil", 40, 90, Accuracy::high, false, false, true},
        {"wrapped, 5 x 5 stencil, float", 48, 120, Accuracy::high, true, false, false},
        {"Ready's clamp, low accuracy", 32, 64, Accuracy::low, false, true, false},
    };
    for (const Case& c : cases) {
        Rule r = gs;
        r.accuracy = c.accuracy;
        r.wrap = c.wrap;
        r.ready_edges = c.ready_edges;
        r.double_precision = c.double_precision;
        const auto start = noise(c.width, c.height, 2);
        const auto one_at_a_time = after(r, c.width, c.height, start, 45, 1, false);
        for (int threads : {1, 2, 3}) {
            int block_steps = 0;
            const auto blocked = after(r, c.width, c.height, start, 45, threads, true, &block_steps);
            INFO(c.name << " on " << threads << " threads, " << block_steps << " steps a block");
            CHECK(block_steps >= 2);  // the run went in blocks
            for (int chem = 0; chem < 2; ++chem) CHECK(same_bits(blocked[chem], one_at_a_time[chem]));
        }
    }
    // A grid too short for blocks (fewer than four bands) goes one step at a time.
    int block_steps = 0;
    after(gs, 32, 8, noise(32, 8, 2), 5, 2, true, &block_steps);
    CHECK(block_steps == 1);
}

TEST_CASE("a step that fails inside a block fails as it does one step at a time", "[formula][blocks]") {
    // a grows by 1 a step; the cell that starts at 27 reaches 40 at step 14's
    // input, where 1 / (a - 40) divides by zero. The laplacian makes each
    // row read the rows beside it.
    Rule r;
    r.chemicals = 1;
    r.parameters = {{"timestep", 1.0}};
    r.code = "delta_a = 1.0f + 0.0f * (laplacian_a + 1.0f / (a - 40.0f));";
    r.ready_edges = false;  // a true torus (Ready's needs a power of two)
    Grid<double> a(96, 64, 0.5);
    a(61, 17) = 27;
    auto failure = [&](bool blocks, int threads, Grid<double>& state, long long& steps, int& block_steps) {
        use_temporal_blocking(blocks);
        Run run(r, 64, 96, {a});
        use_temporal_blocking(true);
        block_steps = run.block_steps();
        std::string what;
        try {
            run.step(3, threads);  // one block, or three steps
            run.step(40, threads);
        } catch (const Unstable& e) {
            what = e.what();
        }
        state = run.chemical(0);
        steps = run.steps();
        return what;
    };
    Grid<double> plain_state, blocked_state;
    long long plain_steps = 0, blocked_steps = 0;
    int block_steps = 0;
    const std::string plain = failure(false, 2, plain_state, plain_steps, block_steps);
    CHECK_THAT(plain, Catch::StartsWith("step 14, cell (x 17, y 61): division by zero"));
    CHECK(plain_steps == 13);
    CHECK(plain_state(61, 17) == 40);
    for (int threads : {1, 2}) {
        const std::string blocked = failure(true, threads, blocked_state, blocked_steps, block_steps);
        CHECK(block_steps >= 2);
        CHECK(blocked == plain);
        CHECK(blocked_steps == plain_steps);
        CHECK(same_bits(blocked_state, plain_state));
    }
}
