#pragma once
// Elementary (Wolfram) cellular automata, the book's Cell1D (Think Complexity
// 2e, chapter 5, used in section 7.5). Rows are time: row i is computed from
// row i - 1. A cell's neighbourhood value is s = 4 * left + 2 * centre + right
// (np.correlate with window [4, 2, 1]) and its new state is bit s of the rule
// number. Beyond the ends is 0 as in np.correlate's 'same' mode, or the row
// wraps around as in the book's Wrap1D.

#include <cstdint>
#include <vector>

#include "sim/boundary.hpp"
#include "sim/grid.hpp"

namespace sim {

struct Cell1DParams {
    int rule = 18;                      // Wolfram rule number, 0..255
    int rows = 32;                      // time steps kept, row 0 included, 1..100000
    int width = 0;                      // cells per row, 1..200001; 0 means 2 * rows + 1
    Boundary boundary = Boundary::zero; // zero beyond the ends as the book, or wrap

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class Cell1D {
public:
    // Row 0 has one on cell, at column width / 2 (the book's start_single).
    explicit Cell1D(const Cell1DParams& params);

    void step();  // fills the next row; throws std::logic_error when all rows are filled
    int rows_filled() const { return rows_filled_; }  // 1 after construction
    const Grid<std::uint8_t>& cells() const { return cells_; }  // rows x width of 0 and 1
    long on_cells() const { return on_cells_; }  // on cells in the filled rows (the book's np.sum(ca.array))

private:
    Cell1DParams params_;
    Grid<std::uint8_t> cells_;
    int rows_filled_ = 1;
    long on_cells_ = 1;
};

// The book's count_cells(rule, n): runs an n-row Cell1D of width 2n + 1 from
// a single cell and returns, for i = 1 .. n - 1, the on cells in the first i
// rows (taken before the i-th step). So element 0 is 1 and there are n - 1.
std::vector<long> count_cells(int rule, int n, Boundary boundary = Boundary::zero);

}  // namespace sim
