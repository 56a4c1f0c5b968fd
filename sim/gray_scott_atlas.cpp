#include "sim/gray_scott_atlas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "sim/check.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/random.hpp"

namespace sim {
namespace {

// The centre of tile i of `count` across [low, high].
double centre(double low, double high, int i, int count) {
    return low + (high - low) * (i + 0.5) / count;
}

// "0.0350": a rate as the messages show it.
std::string rate(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4f", value);
    return text;
}

// The health check every 1000 steps and at the end, as the stepping scenes
// make it at every step: A and B live in [0, 1].
constexpr int health_every = 1000;
constexpr double health_bound = gray_scott_atlas_health_bound;

bool healthy(const GrayScottKernel<float>& kernel) {
    return kernel.within(health_bound);
}

// Throws sim::require_finite's error if the state fails the health check.
// The test reads the float buffers in place; only a failing state is
// converted, to word the message as the other scenes do.
void require_healthy(const GrayScottKernel<float>& kernel, const std::string& run) {
    if (healthy(kernel)) return;
    require_finite(kernel.a(), run + " A", kernel.steps(), health_bound);
    require_finite(kernel.b(), run + " B", kernel.steps(), health_bound);
}

// Whether the run may stop at its current state, and why (TileStop::ran: go on).
TileStop stop_reason(const GrayScottKernel<float>& kernel) {
    const GrayScottParams& p = kernel.params();
    // With B +0 everywhere, A's step is a weighted mean of A's neighbours and
    // 1 with non-negative weights when ra + f <= 1 (see gray_scott.hpp's
    // stability note), so A keeps within its bounds and finite, and B stays +0.
    if (p.ra + p.f <= 1.0 && kernel.b_is_zero()) return TileStop::b_gone;
    if (kernel.unchanged()) return TileStop::fixed_point;
    return TileStop::ran;
}

// One tile's run from the start state, to `steps` or to an early stop, in
// `reused`, the calling thread's kernel (its buffers kept from tile to tile).
GrayScottAtlasTile run_tile(std::optional<GrayScottKernel<float>>& reused, const GrayScottParams& params,
                            const GrayScott& start, int steps, const std::string& name) {
    if (reused)
        reused->restart(params, start.a(), start.b());
    else
        reused.emplace(params, start.a(), start.b());
    GrayScottKernel<float>& kernel = *reused;
    const std::string run = name + " (f = " + rate(params.f) + ", k = " + rate(params.k) + ")";
    constexpr int check = gray_scott_atlas_stop_check;
    TileStop stop = TileStop::ran;
    while (kernel.steps() < steps && stop == TileStop::ran) {
        kernel.step(std::min(check - kernel.steps() % check, steps - kernel.steps()), 1);
        const bool health_due = kernel.steps() % health_every == 0 || kernel.steps() == steps;
        if (health_due) require_healthy(kernel, run);
        stop = stop_reason(kernel);
        // An unhealthy state runs on, to fail where and as the full run does.
        if (stop != TileStop::ran && !health_due && !healthy(kernel)) stop = TileStop::ran;
    }
    return {params.f, params.k, kernel.b_as_stored(), kernel.steps(), stop};
}

}  // namespace

GrayScott gray_scott_atlas_start(const GrayScottAtlasParams& atlas, std::uint64_t seed) {
    atlas.validate();
    Random rng(seed);
    return GrayScott(atlas.base, rng);
}

std::pair<double, double> gray_scott_atlas_rates(const GrayScottAtlasParams& atlas, int index) {
    const int rows = atlas.rows, columns = atlas.columns;
    return {centre(atlas.f_low, atlas.f_high, rows - 1 - index / columns, rows),  // the top row has the largest f
            centre(atlas.k_low, atlas.k_high, index % columns, columns)};
}

GrayScottAtlasTile run_gray_scott_atlas_tile(const GrayScottAtlasParams& atlas, const GrayScott& start, int index,
                                             const std::string& name) {
    if (index < 0 || index >= atlas.columns * atlas.rows)
        throw std::invalid_argument("run_gray_scott_atlas_tile: no tile " + std::to_string(index));
    // Each thread keeps its kernel's buffers from tile to tile.
    thread_local std::optional<GrayScottKernel<float>> kernel;
    GrayScottParams params = atlas.base;
    std::tie(params.f, params.k) = gray_scott_atlas_rates(atlas, index);
    return run_tile(kernel, params, start, atlas.steps, name);
}

Grid<double> gray_scott_atlas_double_b(const GrayScottAtlasParams& atlas, const GrayScott& start, int index) {
    GrayScottParams params = atlas.base;
    std::tie(params.f, params.k) = gray_scott_atlas_rates(atlas, index);
    GrayScottKernel<double> twice(params, start.a(), start.b());
    twice.step(atlas.steps, 1);
    return twice.b();
}

FloatError float_error(const GrayScottAtlasTile& tile, std::span<const double> b, int index) {
    if (b.size() != tile.b.cells().size()) throw std::invalid_argument("float_error: B of another size");
    FloatError e{index, tile.f, tile.k, 0, 0};
    double squares = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        const double d = std::abs(double(tile.b.cells()[i]) - b[i]);
        e.max_abs = std::max(e.max_abs, d);
        squares += d * d;
    }
    e.rms = std::sqrt(squares / double(b.size()));
    return e;
}

std::vector<int> float_error_tiles(const GrayScottAtlasParams& atlas) {
    std::vector<int> tiles;
    for (int quarter : {1, 2, 3}) {
        const int column = quarter * atlas.columns / 4, row = quarter * atlas.rows / 4;
        const int t = std::min(row, atlas.rows - 1) * atlas.columns + std::min(column, atlas.columns - 1);
        if (std::find(tiles.begin(), tiles.end(), t) == tiles.end()) tiles.push_back(t);
    }
    return tiles;
}

const char* to_string(TileStop stop) {
    switch (stop) {
        case TileStop::b_gone:
            return "b_gone";
        case TileStop::fixed_point:
            return "fixed_point";
        case TileStop::ran:
            break;
    }
    return "ran";
}

void GrayScottAtlasParams::validate() const {
    base.validate();
    require_integer("steps", steps, 0, 10'000'000);
    require_integer("columns", columns, 1, 256);
    require_integer("rows", rows, 1, 256);
    for (double f : {f_low, f_high}) require_number("f_range", f, 0.0, 0.2);
    for (double k : {k_low, k_high}) require_number("k_range", k, 0.0, 0.2);
}

std::vector<GrayScottAtlasTile> run_gray_scott_atlas(const GrayScottAtlasParams& atlas, std::uint64_t seed,
                                                     const std::string& name, const std::function<void()>& tile_done) {
    // Every tile starts from the same noise, so the tiles differ only by (f, k).
    const GrayScott start = gray_scott_atlas_start(atlas, seed);
    const int count = atlas.columns * atlas.rows;
    std::vector<GrayScottAtlasTile> tiles(count);
    // The runs, tile by tile across the threads (each run on one thread: at
    // 128^2 cells a step is too short to split, the barrier would cost more).
    // Each tile depends only on its own (f, k), so the order does not matter.
    std::exception_ptr failure;         // an exception must not leave an OpenMP region: kept, rethrown after
    std::exception_ptr report_failure;  // tile_done's, written only inside critical(figgen_progress)
#pragma omp parallel for schedule(dynamic)
    for (int t = 0; t < count; ++t) {
        try {
            tiles[t] = run_gray_scott_atlas_tile(atlas, start, t, name);
        } catch (...) {
#pragma omp critical(figgen_atlas_failure)
            if (!failure) failure = std::current_exception();
        }
        // The progress report formats text: a bad_alloc there must leave
        // neither the critical section nor the region.
#pragma omp critical(figgen_progress)
        {
            try {
                tile_done();
            } catch (...) {
                if (!report_failure) report_failure = std::current_exception();
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
    if (report_failure) std::rethrow_exception(report_failure);
    return tiles;
}

}  // namespace sim
