#pragma once
// Diffusion on a square grid (Think Complexity 2e, section 7.1): each step
//     a += r * correlate(a, [[0,1,0],[1,-4,1],[0,1,0]])
// the explicit 5-point discrete Laplacian. The book's scipy call reads
// zero outside the grid, so mass leaks out at the edges; wrap conserves it.
// The scheme is stable (no value grows, none turns negative) for
// 0 <= r <= 1/4, which validate() enforces.

#include "sim/boundary.hpp"
#include "sim/grid.hpp"

namespace sim {

struct DiffusionParams {
    int n = 9;                          // grid is n x n cells
    double r = 0.1;                     // diffusion rate per step, 0..0.25
    Boundary boundary = Boundary::zero; // zero-fill as the book, or wrap
    int block_row = 3;                  // top-left cell of the initial block
    int block_col = 3;
    int block_size = 3;                 // the block is block_size x block_size cells
    double block_value = 1.0;           // value of each block cell; the rest start at 0

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class Diffusion {
public:
    explicit Diffusion(const DiffusionParams& params);
    // Starts from `initial` (n x n) instead of the block.
    Diffusion(const DiffusionParams& params, Grid<double> initial);

    void step();
    int steps() const { return steps_; }               // steps taken so far
    const Grid<double>& field() const { return a_; }
    const DiffusionParams& params() const { return params_; }
    double total() const;                              // sum of all cells

private:
    DiffusionParams params_;
    Grid<double> a_;
    Grid<double> next_;
    int steps_ = 0;
};

}  // namespace sim
