#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "sim/gray_scott.hpp"
#include "sim/gray_scott_atlas.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/random.hpp"

using sim::GrayScottAtlasParams;
using sim::GrayScottAtlasTile;
using sim::GrayScottKernel;
using sim::TileStop;

namespace {

// Two tiles side by side at f = 0.035 on 64^2 cells: k = 0.057 (the book's
// spots, still moving after 3000 steps) and k = 0.069 (B dies out).
GrayScottAtlasParams spots_and_death() {
    GrayScottAtlasParams atlas;
    atlas.base.n = 64;
    atlas.steps = 3000;
    atlas.columns = 2;
    atlas.rows = 1;
    atlas.f_low = atlas.f_high = 0.035;
    atlas.k_low = 0.051;  // tile centres at 0.057 and 0.069
    atlas.k_high = 0.075;
    return atlas;
}

// The tile's run done the plain way: the kernel stepped to the end, no tests.
sim::Grid<float> full_run(const GrayScottAtlasParams& atlas, const GrayScottAtlasTile& tile, std::uint64_t seed) {
    sim::Random rng(seed);
    const sim::GrayScott start(atlas.base, rng);
    sim::GrayScottParams params = atlas.base;
    params.f = tile.f;
    params.k = tile.k;
    GrayScottKernel<float> kernel(params, start.a(), start.b());
    kernel.step(atlas.steps, 1);
    return kernel.b_as_stored();
}

float largest(const sim::Grid<float>& g) {
    return *std::max_element(g.cells().begin(), g.cells().end());
}

}  // namespace

TEST_CASE("gray-scott atlas: a tile whose B dies stops early with the full run's bits", "[gs_atlas]") {
    const GrayScottAtlasParams atlas = spots_and_death();
    const std::vector<GrayScottAtlasTile> tiles = sim::run_gray_scott_atlas(atlas, 17, "test", [] {});
    REQUIRE(tiles.size() == 2);
    const GrayScottAtlasTile& dead = tiles[1];
    CHECK(dead.k == Approx(0.069));
    // B freezes near 1e-37, not at 0: once (f + k) B is below FLT_MIN the
    // flushed product is 0 and B stops decaying; then A settles, bit for bit.
    CHECK(largest(dead.b) < 1e-30f);
    CHECK(dead.stop == TileStop::fixed_point);
    CHECK(dead.stopped_at < atlas.steps);
    CHECK(dead.stopped_at % sim::gray_scott_atlas_stop_check == 0);
    CHECK(dead.b.cells() == full_run(atlas, dead, 17).cells());
}

TEST_CASE("gray-scott atlas: a tile that keeps its pattern runs every step", "[gs_atlas]") {
    const GrayScottAtlasParams atlas = spots_and_death();
    const std::vector<GrayScottAtlasTile> tiles = sim::run_gray_scott_atlas(atlas, 17, "test", [] {});
    const GrayScottAtlasTile& spots = tiles[0];
    CHECK(spots.k == Approx(0.057));
    CHECK(largest(spots.b) > 0.1f);  // spots: B well above 0 somewhere
    CHECK(spots.stop == TileStop::ran);
    CHECK(spots.stopped_at == atlas.steps);
    CHECK(spots.b.cells() == full_run(atlas, spots, 17).cells());
}

TEST_CASE("gray-scott atlas: B at +0 everywhere stops a tile only where A stays a monotone diffusion", "[gs_atlas]") {
    // No noise and no island: B starts at +0 and A at 1, a state no step changes.
    GrayScottAtlasParams atlas;
    atlas.base.n = 16;
    atlas.base.noise = 0.0;
    atlas.base.island = 0.0;
    atlas.steps = 1000;
    atlas.columns = atlas.rows = 1;
    std::vector<GrayScottAtlasTile> tiles = sim::run_gray_scott_atlas(atlas, 3, "test", [] {});
    CHECK(tiles[0].stop == TileStop::b_gone);
    CHECK(tiles[0].stopped_at == sim::gray_scott_atlas_stop_check);
    CHECK(tiles[0].b.cells() == full_run(atlas, tiles[0], 3).cells());
    // ra + f > 1: A's step is no longer a weighted mean, the B rule does not
    // apply; the state is still a fixed point.
    atlas.base.ra = 1.0;
    atlas.f_low = atlas.f_high = 0.1;
    tiles = sim::run_gray_scott_atlas(atlas, 3, "test", [] {});
    CHECK(tiles[0].stop == TileStop::fixed_point);
    CHECK(tiles[0].stopped_at == sim::gray_scott_atlas_stop_check);
    CHECK(std::string(sim::to_string(TileStop::b_gone)) == "b_gone");
}

TEST_CASE("the atlas's float error is B's difference from the same run in double", "[gray-scott-atlas]") {
    const GrayScottAtlasParams atlas = spots_and_death();
    const auto tiles = sim::run_gray_scott_atlas(atlas, 17, "test atlas", [] {});
    const sim::FloatError spots =
        sim::float_error(tiles[0], sim::gray_scott_atlas_double_b(atlas, sim::gray_scott_atlas_start(atlas, 17), 0).cells(), 0);
    // The same run in double, by the model itself (bit for bit the double kernel).
    sim::Random rng(17);
    sim::GrayScott model(atlas.base, rng);
    sim::GrayScottParams params = atlas.base;
    params.f = tiles[0].f;
    params.k = tiles[0].k;
    sim::GrayScott twice(params, model.a(), model.b());
    for (int s = 0; s < atlas.steps; ++s) twice.step();
    double largest = 0;
    for (std::size_t i = 0; i < twice.b().cells().size(); ++i)
        largest = std::max(largest, std::abs(double(tiles[0].b.cells()[i]) - twice.b().cells()[i]));
    CHECK(spots.max_abs == largest);
    CHECK(spots.max_abs > 0);     // float32 does round differently
    CHECK(spots.max_abs < 1e-3);  // and stays close over 3000 steps
    CHECK(spots.rms <= spots.max_abs);
    CHECK(spots.tile == 0);
    CHECK(spots.k == tiles[0].k);
}

TEST_CASE("the atlas measures float error on its diagonal at a quarter, half and three quarters",
          "[gray-scott-atlas]") {
    GrayScottAtlasParams atlas;
    CHECK(sim::float_error_tiles(atlas) == std::vector<int>{6 * 24 + 6, 12 * 24 + 12, 18 * 24 + 18});
    atlas.columns = atlas.rows = 1;
    CHECK(sim::float_error_tiles(atlas) == std::vector<int>{0});
    atlas.columns = 3;
    atlas.rows = 2;  // rows 0, 1, 1 and columns 0, 1, 2
    CHECK(sim::float_error_tiles(atlas) == std::vector<int>{0, 4, 5});
}
