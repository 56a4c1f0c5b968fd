#pragma once
// The forest-fire model of Bak, Chen & Tang (1990), Think Complexity 2e
// exercise 7.2. Cells are empty (0), a tree (1) or on fire (5) on a torus.
// Each step, synchronously from the old state:
//     empty -> tree  with probability p
//     tree  -> fire  if a von Neumann neighbour burns, else with probability f
//     fire  -> empty
//
// Randomness: every step draws one rng.uniform() per cell, row by row, for
// every cell whatever its state (a burning cell's draw is thrown away). The
// stream then does not depend on the state, so the draw that decides a cell
// at step t is the same in any two runs with the same seed, and one changed
// cell cannot shift every later draw.

#include <cstdint>

#include "sim/grid.hpp"
#include "sim/random.hpp"

namespace sim {

struct ForestFireParams {
    int n = 200;                   // grid is n x n cells, wrapped into a torus, 3..8192
    double p = 0.01;               // probability that an empty cell grows a tree, 0..1
    double f = 0.001;              // probability that a tree with no burning neighbour ignites, 0..1
    double initial_density = 0.01; // each cell starts a tree with this probability (the catalog: p), 0..1

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class ForestFire {
public:
    static constexpr std::uint8_t empty = 0, tree = 1, fire = 5;

    // Owns its generator: one uniform() per cell, row by row, plants the
    // initial trees; the steps continue the same stream.
    ForestFire(const ForestFireParams& params, std::uint64_t seed);
    // Starts from the given n x n grid of 0, 1 and 5 instead (no draws).
    ForestFire(const ForestFireParams& params, Grid<std::uint8_t> cells, std::uint64_t seed);

    void step();
    const Grid<std::uint8_t>& cells() const { return cells_; }
    long trees() const { return trees_; }
    long fires() const { return fires_; }
    long empties() const { return static_cast<long>(cells_.size()) - trees_ - fires_; }
    int steps() const { return steps_; }  // steps taken so far
    const ForestFireParams& params() const { return params_; }

private:
    void count();  // sets trees_ and fires_ from the cells

    ForestFireParams params_;
    Random rng_;
    Grid<std::uint8_t> cells_;
    Grid<std::uint8_t> next_;  // written by step(), then swapped in
    long trees_ = 0, fires_ = 0;
    int steps_ = 0;
};

}  // namespace sim
