// gs-atlas: a map of Gray-Scott patterns over a grid of (f, k), in the manner
// of Pearson (Science 1993): each tile is one run from the same start, its B
// drawn through Blues; f rises upwards, k to the right. It shows off the fast
// float kernel (sim/gray_scott_kernels): 576 runs of 128^2 cells x 10,000
// steps in about 37 s on two cores.
#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

#include "figures/field_spec.hpp"
#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "sim/check.hpp"
#include "sim/gray_scott.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/random.hpp"

namespace figures {

void render_gray_scott_atlas(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"n", "cells a side of each run"},
                     {"steps", "steps of each run"},
                     {"f_range", "[lowest, highest] feed rate, rows from bottom to top"},
                     {"k_range", "[lowest, highest] kill rate, columns from left to right"},
                     {"tiles", "[columns, rows] of the map"},
                     {"ra", "diffusion rate of A"},
                     {"rb", "diffusion rate of B"},
                     {"noise", "B starts uniform in [0, noise)"},
                     {"island", "added to B on the central square"}});
    Settings style("style", d.style, with_plot_style_keys(field_spec_keys()));
    sim::GrayScottParams base;
    int steps = 0, columns = 0, rows = 0;
    std::vector<double> f_range, k_range;
    try {
        base.n = params.count("n", 128);
        base.ra = params.number("ra", base.ra);
        base.rb = params.number("rb", base.rb);
        base.noise = params.number("noise", base.noise);
        base.island = params.number("island", base.island);
        steps = params.count("steps", 10000);
        sim::require_integer("steps", steps, 0, 10'000'000);
        f_range = params.numbers("f_range", {0.01, 0.07});
        k_range = params.numbers("k_range", {0.04, 0.07});
        const auto tiles = params.integers("tiles", {24, 24});
        if (f_range.size() != 2 || k_range.size() != 2 || tiles.size() != 2)
            throw std::invalid_argument("f_range and k_range must be [low, high] and tiles [columns, rows]");
        sim::require_integer("tiles columns", tiles[0], 1, 64);
        sim::require_integer("tiles rows", tiles[1], 1, 64);
        columns = int(tiles[0]);
        rows = int(tiles[1]);
        for (double f : f_range) sim::require_number("f_range", f, 0.0, 0.2);
        for (double k : k_range) sim::require_number("k_range", k, 0.0, 0.2);
        base.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const FieldSpec spec = read_field_spec(style, {render::colormap("Blues"), {}, {}, 1.0f, render::Sampling::smooth});
    progress.start(d.id, static_cast<long long>(columns) * rows);

    // The starting A and B, each tile's B kept for drawing, and per thread
    // a float kernel's padded A, B and their next steps.
    require_memory(d, options,
                   {grid_need("grids of doubles", base.n, base.n, 8, 2.0 + double(columns) * rows),
                    grid_need("kernel grids of floats", base.n + 2, base.n + 2, 4, 4.0 * std::max(1u, std::thread::hardware_concurrency()))});
    // Every tile starts from the same noise, so the tiles differ only by (f, k).
    sim::Random rng(d.seed);
    const sim::GrayScott start(base, rng);
    auto centre = [](const std::vector<double>& range, int i, int count) {
        return range[0] + (range[1] - range[0]) * (i + 0.5) / count;
    };
    // The runs, tile by tile across the threads (each run on one thread: at
    // 128^2 cells a step is too short to split, the barrier would cost more).
    // Each tile depends only on its own (f, k), so the order does not matter.
    const int count = columns * rows;
    std::vector<sim::GrayScottParams> runs(count, base);
    for (int t = 0; t < count; ++t) {
        runs[t].f = centre(f_range, rows - 1 - t / columns, rows);  // f rises upwards: the top row has the largest f
        runs[t].k = centre(k_range, t % columns, columns);
    }
    std::vector<sim::Grid<double>> results(count);
    std::exception_ptr failure;  // an exception must not leave an OpenMP region: kept, rethrown after
#pragma omp parallel for schedule(dynamic)
    for (int t = 0; t < count; ++t) {
        try {
            sim::GrayScottKernel<float> kernel(runs[t], start.a(), start.b());
            // The health check every 1000 steps and at the end, as the
            // stepping scenes do at every step: A and B live in [0, 1].
            for (int done = 0; done < steps;) {
                const int chunk = std::min(1000, steps - done);
                kernel.step(chunk, 1);
                done += chunk;
                const std::string run = d.id + " (f = " + format_fixed(runs[t].f, 4) + ", k = " +
                                        format_fixed(runs[t].k, 4) + ")";
                require_finite(kernel.a(), run + " A", done, 10.0);
                require_finite(kernel.b(), run + " B", done, 10.0);
            }
            results[t] = kernel.b();
        } catch (...) {
#pragma omp critical(figgen_atlas_failure)
            if (!failure) failure = std::current_exception();
        }
#pragma omp critical(figgen_progress)
        progress.advance();
    }
    if (failure) std::rethrow_exception(failure);

    std::vector<FieldLayer> tiles;
    nlohmann::json tile_meta = nlohmann::json::array();
    for (int t = 0; t < count; ++t) {
        const sim::Grid<double>& b = results[t];
        for (double v : b.cells())
            if (!std::isfinite(v))
                throw std::runtime_error(d.id + ": the run at f = " + format_fixed(runs[t].f, 4) + ", k = " +
                                         format_fixed(runs[t].k, 4) + " went numerically unstable; no image written");
        tiles.push_back(field_layer(b, spec));
        // Where the spots die B decays towards 0 and, as the float kernel
        // flushes subnormals, stops near 1e-38 instead: a tile whose B is
        // below 1e-20 everywhere holds no chemical, and is drawn flat (as
        // matplotlib draws an empty range), not as an autoscaled picture of
        // rounding.
        if (!spec.vmin && !spec.vmax && tiles.back().style.vmax < 1e-20)
            tiles.back().style.vmax = tiles.back().style.vmin + 1;
        double mean = 0;
        for (double v : b.cells()) mean += v;
        tile_meta.push_back({{"f", runs[t].f},
                             {"k", runs[t].k},
                             {"mean_B", mean / double(b.size())},
                             {"state_sha256", state_hash(b)}});
    }

    const int width = figure_width(d, options), height = figure_height(d, options);
    const render::PlotStyle plot = read_plot_style(style, options.scale);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    // The plot frame, made square, holds the tiles; then the axes are drawn over it.
    render::Rect frame = render::plot_row(width, height, 1, plot)[0];
    const float side = std::min(frame.w, frame.h);
    frame.x += (frame.w - side) / 2;
    frame.w = frame.h = side;
    const float tw = side / float(columns), th = side / float(rows);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            const FieldLayer& t = tiles[r * columns + c];
            render::draw_field(canvas, {frame.x + c * tw, frame.y + r * th, tw, th}, t.rows, t.cols, t.values, t.style);
        }
    render::Axes axes;
    axes.x_range = std::pair{k_range[0], k_range[1]};
    axes.y_range = std::pair{f_range[0], f_range[1]};
    axes.x_label = "kill rate k";
    axes.y_label = "feed rate f";
    axes.title =
        "Gray-Scott B after " + std::to_string(steps) + " steps, " + std::to_string(base.n) + "\u00b2 cells each";
    render::draw_axes(canvas, frame, axes, plot);
    write_figure(d, options, canvas.read(), {{"params", params.used()}, {"style", style.used()}, {"tiles", tile_meta}});
    progress.finish();
}

}  // namespace figures
