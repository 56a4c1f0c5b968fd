#pragma once
// A map of Gray-Scott patterns over a grid of (f, k), in the manner of
// Pearson (Science 1993): each tile is one run of the fast float kernel
// (sim/gray_scott_kernels.hpp) from the same start, so the tiles differ only
// by their feed and kill rates.

#include <cstdint>
#include <functional>
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
    int columns = 24, rows = 24;         // tiles of the map, 1..64 each

    void validate() const;  // throws ParameterError naming the bad parameter
};

struct GrayScottAtlasTile {
    double f = 0, k = 0;  // the run's rates: the centre of its tile
    Grid<double> b;       // B after the last step
};

// Runs every tile, in row-major order from the top row down: f rises
// upwards (the top row has the largest f), k to the right. Every run starts
// from the same GrayScott(base, Random(seed)) state. The runs go across the
// OpenMP threads, each on one thread; `tile_done` is called once per
// finished tile, one call at a time. A run whose A or B leaves [-10, 10] or
// turns non-finite (checked every 1000 steps and at the end) throws
// std::runtime_error "<name> (f = 0.0350, k = 0.0570) B went numerically
// unstable at step ...": `name` is what the message calls the atlas.
std::vector<GrayScottAtlasTile> run_gray_scott_atlas(const GrayScottAtlasParams& atlas, std::uint64_t seed,
                                                     const std::string& name, const std::function<void()>& tile_done);

}  // namespace sim
