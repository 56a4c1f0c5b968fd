#pragma once
// A map of Gray-Scott patterns over a grid of (f, k), in the manner of
// Pearson (Science 1993): each tile is one run of the fast float kernel
// (sim/gray_scott_kernels.hpp) from the same start, so the tiles differ only
// by their feed and kill rates.

#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <string>
#include <vector>

#include "sim/gray_scott.hpp"
#include "sim/grid.hpp"

namespace sim {

struct GrayScottAtlasParams {
    GrayScottParams base;                // n, ra, rb, noise, island of every run (its f and k are the tiles')
    int steps = 10000;                   // steps of each run, 0..10,000,000
    double f_low = 0.01, f_high = 0.07;  // f_range: the feed rate at the map's bottom and top edges, 0..0.2
    double k_low = 0.04, k_high = 0.07;  // k_range: the kill rate at its left and right edges, 0..0.2
    int columns = 24, rows = 24;         // tiles of the map, 1..256 each (a cluster runs 96 x 96)

    void validate() const;  // throws ParameterError naming the bad parameter
};

// Why a tile's run ended before `steps`. Both are exact: the run's later
// steps would leave the B it shows (and passes the health check) as it is.
enum class TileStop {
    ran,          // it ran every step
    b_gone,       // B was +0 in every cell: it stays +0 whatever A does (A then obeys
                  // a monotone diffusion towards 1 when ra + f <= 1, so it stays healthy)
    fixed_point,  // a step left every cell of A and B with the same bits: so would every later one
};
const char* to_string(TileStop stop);  // "ran", "b_gone", "fixed_point"

struct GrayScottAtlasTile {
    double f = 0, k = 0;  // the run's rates: the centre of its tile
    Grid<float> b;        // B after the last step, as the float kernel holds it
    int stopped_at = 0;   // the step its run stopped: `steps` unless it stopped early
    TileStop stop = TileStop::ran;
};

// How often a run tests for an early stop (steps; the health check's 1000
// is a multiple). A test reads the kernel's buffers in place and costs about
// two steps of a 128^2 run, so 100 adds ~2% and stops at most 99 steps late.
inline constexpr int gray_scott_atlas_stop_check = 100;

// A finished run's A and B lie within [-bound, bound]: a run that leaves it
// is refused as unstable (see run_gray_scott_atlas).
inline constexpr double gray_scott_atlas_health_bound = 10.0;

// Runs every tile, in row-major order from the top row down: f rises
// upwards (the top row has the largest f), k to the right. Every run starts
// from the same GrayScott(base, Random(seed)) state. The runs go across the
// OpenMP threads, each on one thread; `tile_done` is called once per
// finished tile, one call at a time. A run whose A or B leaves [-10, 10] or
// turns non-finite (checked every 1000 steps and at the end) throws
// std::runtime_error "<name> (f = 0.0350, k = 0.0570) B went numerically
// unstable at step ...": `name` is what the message calls the atlas. A run
// stops early (see TileStop; tested every gray_scott_atlas_stop_check steps)
// only where its state passes that check, so its B, and any failure, are
// those of the full run.
std::vector<GrayScottAtlasTile> run_gray_scott_atlas(const GrayScottAtlasParams& atlas, std::uint64_t seed,
                                                     const std::string& name, const std::function<void()>& tile_done);

// The tiles one at a time (what run_gray_scott_atlas does on every
// thread), for a caller that spreads them itself (a figure's work items):
// the start every tile runs from, tile `index`'s (f, k), and its run on the
// calling thread (which keeps its kernel's buffers for its next tile).
GrayScott gray_scott_atlas_start(const GrayScottAtlasParams& atlas, std::uint64_t seed);
std::pair<double, double> gray_scott_atlas_rates(const GrayScottAtlasParams& atlas, int index);
GrayScottAtlasTile run_gray_scott_atlas_tile(const GrayScottAtlasParams& atlas, const GrayScott& start, int index,
                                             const std::string& name);

// What float32 costs the atlas: tile `index`'s run again in double (the
// double kernel, which equals sim::GrayScott bit for bit, every step), and
// B's largest and RMS difference from the float tile's.
struct FloatError {
    int tile = 0;
    double f = 0, k = 0;
    double max_abs = 0, rms = 0;
};
Grid<double> gray_scott_atlas_double_b(const GrayScottAtlasParams& atlas, const GrayScott& start, int index);
FloatError float_error(const GrayScottAtlasTile& tile, std::span<const double> b, int index);
// The tiles the figure measures that on: the map's diagonal at 1/4, 1/2 and
// 3/4 of the way (fewer on a map of fewer tiles).
std::vector<int> float_error_tiles(const GrayScottAtlasParams& atlas);

}  // namespace sim
