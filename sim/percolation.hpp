#pragma once
// Percolation as a cellular automaton (Think Complexity 2e, section 7.3).
// Cells are blocked (0), porous (1) or wet (5); the top row starts wet. Each
// step, synchronously, a porous cell with a wet von Neumann neighbour becomes
// wet; outside the grid is blocked (the book's zero-filled correlate2d, whose
// sum reaches 5 only with a wet neighbour, since four porous ones give 4).

#include <cstdint>
#include <vector>

#include "sim/grid.hpp"
#include "sim/random.hpp"

namespace sim {

struct PercolationParams {
    int n = 10;      // grid is n x n cells, 1..8192
    double q = 0.7;  // probability that a cell is porous, 0..1

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class Percolation {
public:
    static constexpr std::uint8_t blocked = 0, porous = 1, wet = 5;

    // One rng.uniform() per cell, row by row, for all n x n cells (porous when
    // uniform() < q, as the book's np.random.choice), then the top row is wet.
    Percolation(const PercolationParams& params, Random& rng);
    // Starts from the given grid (any size, at least 1x1) of 0, 1 and 5, wet
    // where it says so (for tests).
    explicit Percolation(Grid<std::uint8_t> cells);

    long step();  // returns the number of cells that became wet
    const Grid<std::uint8_t>& cells() const { return cells_; }
    long wet_count() const { return wet_count_; }         // the book's num_wet
    bool bottom_row_wet() const { return bottom_wet_ > 0; }
    int steps() const { return steps_; }                  // steps taken so far

private:
    void start();  // counts the wet cells and makes them the first front

    Grid<std::uint8_t> cells_;
    std::vector<int> front_;  // cells (row * cols + col) wetted by the last step
    std::vector<int> next_front_;
    long wet_count_ = 0;
    long bottom_wet_ = 0;     // wet cells in the bottom row
    int steps_ = 0;
};

enum class PercolationStop {
    bottom_row_wet,  // a wet path joins the top and bottom rows
    fixed_point,     // a step wetted nothing
};

struct PercolationRun {
    bool percolates;         // the bottom row is wet when the run stops
    PercolationStop reason;  // why the run stopped
    int steps;               // step() calls made by this run, the last included
};

// The book's test_perc: steps until the bottom row is wet (percolates) or a
// step leaves the wet count unchanged (does not). At least one step is taken.
PercolationRun run_to_bottom_or_fixed_point(Percolation& model);
// Steps on past the bottom row until a step wets nothing; always stops at the
// fixed point, with percolates = bottom row wet there.
PercolationRun run_to_fixed_point(Percolation& model);

// The book's find_critical: from q = start, `iterations` runs of test_perc on
// fresh n x n models drawn from rng, each stepping q down by `step` when it
// percolates and up when it does not (q is clamped to [0, 1] for the run).
// Returns every q visited, start first (iterations + 1 values); their mean
// estimates the critical q.
std::vector<double> find_critical(int n, double start, double step, int iterations, Random& rng);

}  // namespace sim
