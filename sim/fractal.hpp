#pragma once
// Straight-line fits and fractal dimensions (Think Complexity 2e, sections
// 7.5-7.8): a log-log slope of a count against a size estimates a dimension.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sim/grid.hpp"

namespace sim {

struct LineFit {
    double slope;        // least-squares slope of y on x
    double intercept;    // y at x = 0
    double r;            // Pearson correlation, 0 when x or y is constant (as scipy)
    std::size_t points;  // number of (x, y) pairs fitted
};

// Ordinary least squares, as scipy.stats.linregress. Throws
// std::invalid_argument when the sizes differ, there are fewer than 2
// points, a value is not finite, or every x is the same.
LineFit fit_line(std::span<const double> x, std::span<const double> y);
// fit_line on natural logs of x and y; also throws on a value <= 0.
LineFit fit_log_log(std::span<const double> x, std::span<const double> y);
// The fitted power law exp(intercept) * x^slope of a fit_log_log result, at each x.
std::vector<double> power_law(const LineFit& log_fit, std::span<const double> x);

struct BoxCount {
    std::vector<int> box_sizes;  // s = 1, 2, 4, ...
    std::vector<long> occupied;  // boxes of s x s cells holding at least one cell in the state
    LineFit fit;                 // log occupied against log s
    double dimension;            // -fit.slope
};

// Box counting: the grid is tiled with s x s boxes from the top-left corner
// for s = 1, 2, 4, ... up to `largest` (0 means min(rows, cols) / 4). Partial
// boxes at the right and bottom edges are counted like whole ones: dropping
// them would miss occupied cells and bend the small-s end of the line.
// Throws std::invalid_argument when fewer than 2 sizes fit or no cell is in
// the state (log 0 has no line).
BoxCount box_count(const Grid<std::uint8_t>& cells, std::uint8_t state, int largest = 0);

struct MassScaling {
    std::vector<int> sizes;  // box side i = 1, 3, 5, ... < min(rows, cols)
    std::vector<long> mass;  // cells in the state in the centred i x i box
    LineFit fit;             // log mass against log i, over the sizes with mass > 0
};

// The book's solution to exercise 7.2: cells in the state in centred boxes
// (top = (rows - i) / 2, left = (cols - i) / 2) of growing odd side i. Throws
// std::invalid_argument when fewer than 2 boxes hold such a cell.
MassScaling central_box_mass(const Grid<std::uint8_t>& cells, std::uint8_t state);

}  // namespace sim
