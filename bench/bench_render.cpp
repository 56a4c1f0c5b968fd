// Rendering and encoding throughput: what a figure's frames cost.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/gl/canvas.hpp"
#include "render/hex_cells.hpp"
#include "render/isosurface.hpp"
#include "render/tubes.hpp"
#include "app/render/frame_canvas.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "sim/diffusion.hpp"

namespace {

scenes::FieldPanel diffusion_panel(int n) {
    sim::DiffusionParams p;
    p.n = n;
    p.block_row = p.block_col = n / 3;
    p.block_size = n / 3;
    sim::Diffusion model(p);
    for (int i = 0; i < 10; ++i) model.step();
    return {"step 10",
            {{n, n, model.field().cells(), {&render::colormap("Reds"), 0, 1, 0.8f, render::Sampling::nearest}}}};
}

}  // namespace

// One 900x450 three-panel figure: canvas, fields, frames, titles, read-back.
static void draw_three_panels(benchmark::State& state) {
    const auto panel = diffusion_panel(static_cast<int>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(app::drawn_image(scenes::field_page({panel, panel, panel}, 900, 450, 1.0), 900, 450));
}
BENCHMARK(draw_three_panels)->Arg(9)->Arg(300)->Unit(benchmark::kMillisecond);

// Encoding a 480x520 frame with libx264 (2 pinned threads).
static void encode_frame(benchmark::State& state) {
    const auto frame = app::drawn_image(scenes::field_page({diffusion_panel(9)}, 480, 520, 1.0), 480, 520);
    const auto path = std::filesystem::temp_directory_path() / "figgen-bench.mp4";
    {
        media::VideoWriter video(path, frame.width, frame.height);
        for (auto _ : state) video.add(frame);
        video.finish();
    }
    std::filesystem::remove(path);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(encode_frame)->Unit(benchmark::kMillisecond);

// Writing the 900x450 figure PNG.
static void write_figure_png(benchmark::State& state) {
    const auto image = app::drawn_image(scenes::field_page({diffusion_panel(9)}, 900, 450, 1.0), 900, 450);
    const auto path = std::filesystem::temp_directory_path() / "figgen-bench.png";
    for (auto _ : state) media::write_png(path, image);
    std::filesystem::remove(path);
}
BENCHMARK(write_figure_png)->Unit(benchmark::kMillisecond);

// A Gray-Scott animation frame's panel: two smoothly sampled 100x100 layers.
static scenes::FieldPanel smooth_frame_panel() {
    std::vector<double> values(100 * 100);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 + 0.5 * std::sin(0.37 * double(i));
    scenes::FieldPanel panel{"step 1000", {}};
    for (const char* map : {"Reds", "Blues"})
        panel.layers.push_back({100, 100, values, {&render::colormap(map), 0, 1, 0.7f, render::Sampling::smooth}});
    return panel;
}

// That frame at 480x520 as a figure draws it: four samples, a pass per layer.
static void draw_smooth_frame(benchmark::State& state) {
    const scenes::FieldPanel panel = smooth_frame_panel();
    for (auto _ : state) benchmark::DoNotOptimize(app::drawn_image(scenes::field_page({panel}, 480, 520, 1.0), 480, 520));
}
BENCHMARK(draw_smooth_frame)->Unit(benchmark::kMillisecond);

// The same frame as a film draws it: one sample, both layers in one pass.
static void draw_smooth_frame_paired(benchmark::State& state) {
    const scenes::FieldPanel panel = smooth_frame_panel();
    render::Canvas canvas(480, 520, 1);
    for (auto _ : state) {
        scenes::paint_field_panels(canvas, {panel}, 1.0, scenes::LayerPasses::paired);
        benchmark::DoNotOptimize(canvas.read());
    }
}
BENCHMARK(draw_smooth_frame_paired)->Unit(benchmark::kMillisecond);

// An empty 480x520 canvas: creating its framebuffers, clearing, resolving, reading back.
static void empty_canvas(benchmark::State& state) {
    for (auto _ : state) {
        render::Canvas canvas(480, 520);
        canvas.clear({1, 1, 1, 1});
        benchmark::DoNotOptimize(canvas.read());
    }
}
BENCHMARK(empty_canvas)->Unit(benchmark::kMillisecond);

// A crystal of about 100,000 cells (hex radius 182) drawn as hexagons: one instanced call.
static void draw_hex_crystal(benchmark::State& state) {
    std::vector<glm::ivec2> cells;
    const int radius = 182;
    for (int q = -radius; q <= radius; ++q)
        for (int r = -radius; r <= radius; ++r)
            if (std::max({std::abs(q), std::abs(r), std::abs(q + r)}) <= radius) cells.push_back({q, r});
    render::Canvas canvas(900, 900);
    const auto view = render::fit_hex_view({0, 0, 900, 900}, radius);
    for (auto _ : state) {
        canvas.clear({1, 1, 1, 1});
        render::draw_hex_cells(canvas, view, cells, {0.1f, 0.3f, 0.55f, 1});
        benchmark::DoNotOptimize(canvas.read());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<long>(cells.size()));
}
BENCHMARK(draw_hex_crystal)->Unit(benchmark::kMillisecond);

// The isosurface of a 128^3 field extracted and drawn, lit, into a 480x480
// frame as a 3-D formula figure's film draws it (scenes/formula.cpp): a
// gyroid, sin x cos y + sin y cos z + sin z cos x with four periods a side,
// at level 0.25, capped on the grid's faces: 718k facets at every cell,
// more than the frame's budget (render::facets_for_pixels), so every second
// cell is sampled, as the formula figure does; more than Ready's 3-D
// patterns make. Issue 48's target: under 0.3 s.
namespace {
constexpr int gyroid_n = 128;
std::vector<double> gyroid() {
    const int n = gyroid_n;
    std::vector<double> values(static_cast<std::size_t>(n) * n * n);
    const double k = 2 * M_PI * 4 / n;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                values[(static_cast<std::size_t>(z) * n + y) * n + x] = std::sin(k * x) * std::cos(k * y) +
                                                                        std::sin(k * y) * std::cos(k * z) +
                                                                        std::sin(k * z) * std::cos(k * x);
    return values;
}
std::vector<render::Facet> gyroid_surface(const std::vector<double>& values) {
    const render::IsosurfaceGrid grid{gyroid_n, gyroid_n, gyroid_n, values};
    return render::isosurface_within(grid, 0.25, {0.4f, 0.7f, 0.4f, 1.0f}, render::facets_for_pixels(480 * 480));
}
render::Image draw_gyroid(const std::vector<render::Facet>& surface, int samples) {
    const float far = float(gyroid_n - 1);
    const render::Camera camera = render::frame_bounds({0, 0, 0}, {far, far, far}, 35, 25, 1.0f);
    const scenes::FrameDrawing frame{[&](render::Surface& s) {
                                         s.background({1, 1, 1, 1});
                                         render::draw_tubes(s, {0, 0, 480, 480}, {}, surface, camera);
                                     },
                                     samples, true};
    return app::drawn_image(frame, 480, 480);
}
}  // namespace

static void isosurface_128(benchmark::State& state) {
    const std::vector<double> values = gyroid();
    std::size_t facets = 0;
    for (auto _ : state) {
        const std::vector<render::Facet> surface = gyroid_surface(values);
        facets = surface.size();
        benchmark::DoNotOptimize(draw_gyroid(surface, 4));
    }
    state.counters["facets"] = static_cast<double>(facets);
}
BENCHMARK(isosurface_128)->Unit(benchmark::kMillisecond);

// Its parts: the extraction alone, and the drawing alone with 4 samples
// (as films draw) and with 1.
static void isosurface_128_extract(benchmark::State& state) {
    const std::vector<double> values = gyroid();
    for (auto _ : state) benchmark::DoNotOptimize(gyroid_surface(values));
}
BENCHMARK(isosurface_128_extract)->Unit(benchmark::kMillisecond);
static void isosurface_128_draw(benchmark::State& state) {
    const std::vector<render::Facet> surface = gyroid_surface(gyroid());
    for (auto _ : state) benchmark::DoNotOptimize(draw_gyroid(surface, static_cast<int>(state.range(0))));
}
BENCHMARK(isosurface_128_draw)->Arg(4)->Arg(1)->Unit(benchmark::kMillisecond);
