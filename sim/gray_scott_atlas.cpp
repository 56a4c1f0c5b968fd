#include "sim/gray_scott_atlas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "sim/check.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/random.hpp"

namespace sim {
namespace {

// The centre of tile i of `count` across [low, high].
double centre(double low, double high, int i, int count) { return low + (high - low) * (i + 0.5) / count; }

// "0.0350": a rate as the messages show it.
std::string rate(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4f", value);
    return text;
}


// One tile's run from the start state.
Grid<double> run_tile(const GrayScottParams& params, const GrayScott& start, int steps, const std::string& name) {
    GrayScottKernel<float> kernel(params, start.a(), start.b());
    const std::string run = name + " (f = " + rate(params.f) + ", k = " + rate(params.k) + ")";
    // The health check every 1000 steps and at the end, as the stepping
    // scenes do at every step: A and B live in [0, 1].
    for (int done = 0; done < steps;) {
        const int chunk = std::min(1000, steps - done);
        kernel.step(chunk, 1);
        done += chunk;
        require_finite(kernel.a(), run + " A", done, 10.0);
        require_finite(kernel.b(), run + " B", done, 10.0);
    }
    return kernel.b();
}

}  // namespace

void GrayScottAtlasParams::validate() const {
    base.validate();
    require_integer("steps", steps, 0, 10'000'000);
    require_integer("columns", columns, 1, 64);
    require_integer("rows", rows, 1, 64);
    for (double f : {f_low, f_high}) require_number("f_range", f, 0.0, 0.2);
    for (double k : {k_low, k_high}) require_number("k_range", k, 0.0, 0.2);
}

std::vector<GrayScottAtlasTile> run_gray_scott_atlas(const GrayScottAtlasParams& atlas, std::uint64_t seed,
                                                     const std::string& name, const std::function<void()>& tile_done) {
    atlas.validate();
    // Every tile starts from the same noise, so the tiles differ only by (f, k).
    Random rng(seed);
    const GrayScott start(atlas.base, rng);
    const int columns = atlas.columns, rows = atlas.rows, count = columns * rows;
    std::vector<GrayScottAtlasTile> tiles(count);
    for (int t = 0; t < count; ++t) {
        tiles[t].f = centre(atlas.f_low, atlas.f_high, rows - 1 - t / columns, rows);  // the top row has the largest f
        tiles[t].k = centre(atlas.k_low, atlas.k_high, t % columns, columns);
    }
    // The runs, tile by tile across the threads (each run on one thread: at
    // 128^2 cells a step is too short to split, the barrier would cost more).
    // Each tile depends only on its own (f, k), so the order does not matter.
    std::exception_ptr failure;  // an exception must not leave an OpenMP region: kept, rethrown after
    std::exception_ptr report_failure;  // tile_done's, written only inside critical(figgen_progress)
#pragma omp parallel for schedule(dynamic)
    for (int t = 0; t < count; ++t) {
        try {
            GrayScottParams params = atlas.base;
            params.f = tiles[t].f;
            params.k = tiles[t].k;
            tiles[t].b = run_tile(params, start, atlas.steps, name);
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
