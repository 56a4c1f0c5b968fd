#include "sim/fractal.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace sim {

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
    if (x.size() != y.size())
        throw std::invalid_argument("fit_line: " + std::to_string(x.size()) + " x values but " +
                                    std::to_string(y.size()) + " y values");
    const std::size_t n = x.size();
    if (n < 2) throw std::invalid_argument("fit_line: " + std::to_string(n) + " points, a line needs at least 2");
    double x_sum = 0, y_sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
            throw std::invalid_argument("fit_line: point " + std::to_string(i) + " is not finite");
        x_sum += x[i];
        y_sum += y[i];
    }
    const double x_mean = x_sum / static_cast<double>(n), y_mean = y_sum / static_cast<double>(n);
    // Centred sums (two passes): no cancellation between large squares.
    double sxx = 0, syy = 0, sxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double dx = x[i] - x_mean, dy = y[i] - y_mean;
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    if (sxx == 0) throw std::invalid_argument("fit_line: every x is the same, the slope is undefined");
    const double slope = sxy / sxx;
    const double denominator = std::sqrt(sxx * syy);
    const double r = denominator == 0 ? 0.0 : std::clamp(sxy / denominator, -1.0, 1.0);
    return {slope, y_mean - slope * x_mean, r, n};
}

LineFit fit_log_log(std::span<const double> x, std::span<const double> y) {
    if (x.size() != y.size())
        throw std::invalid_argument("fit_log_log: " + std::to_string(x.size()) + " x values but " +
                                    std::to_string(y.size()) + " y values");
    std::vector<double> log_x(x.size()), log_y(y.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!(x[i] > 0) || !(y[i] > 0))
            throw std::invalid_argument("fit_log_log: point " + std::to_string(i) +
                                        " has a value <= 0 (or NaN), which has no logarithm");
        log_x[i] = std::log(x[i]);
        log_y[i] = std::log(y[i]);
    }
    return fit_line(log_x, log_y);
}

BoxCount box_count(const Grid<std::uint8_t>& cells, std::uint8_t state, int largest) {
    const int rows = cells.rows(), cols = cells.cols();
    if (largest == 0) largest = std::min(rows, cols) / 4;
    if (largest < 2)
        throw std::invalid_argument("box_count: largest box = " + std::to_string(largest) +
                                    " is too small: a fit needs boxes of sizes 1 and 2 at least (8x8 cells)");
    // Occupancy of the boxes of the current size; each doubling ORs 2x2
    // blocks of it, since boxes tiled from the top-left corner nest exactly.
    int box_rows = rows, box_cols = cols;
    std::vector<std::uint8_t> occupied(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) occupied[i] = cells.cells()[i] == state;
    BoxCount result;
    std::vector<double> sizes, counts;
    for (int s = 1; s <= largest; s *= 2) {
        if (s > 1) {
            const int coarse_rows = (box_rows + 1) / 2, coarse_cols = (box_cols + 1) / 2;
            std::vector<std::uint8_t> coarse(static_cast<std::size_t>(coarse_rows) * coarse_cols, 0);
            for (int i = 0; i < box_rows; ++i)
                for (int j = 0; j < box_cols; ++j)
                    coarse[static_cast<std::size_t>(i / 2) * coarse_cols + j / 2] |=
                        occupied[static_cast<std::size_t>(i) * box_cols + j];
            occupied = std::move(coarse);
            box_rows = coarse_rows;
            box_cols = coarse_cols;
        }
        long count = 0;
        for (std::uint8_t o : occupied) count += o;
        if (count == 0)
            throw std::invalid_argument("box_count: no cell is in state " + std::to_string(state));
        result.box_sizes.push_back(s);
        result.occupied.push_back(count);
        sizes.push_back(s);
        counts.push_back(static_cast<double>(count));
    }
    result.fit = fit_log_log(sizes, counts);
    result.dimension = -result.fit.slope;
    return result;
}

MassScaling central_box_mass(const Grid<std::uint8_t>& cells, std::uint8_t state) {
    const int rows = cells.rows(), cols = cells.cols();
    // Summed-area table: prefix(i, j) = cells in the state above and left of (i, j).
    Grid<long> prefix(rows + 1, cols + 1, 0);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j)
            prefix(i + 1, j + 1) = prefix(i, j + 1) + prefix(i + 1, j) - prefix(i, j) + (cells(i, j) == state);
    MassScaling result;
    std::vector<double> sizes, masses;
    for (int i = 1; i < std::min(rows, cols); i += 2) {
        const int top = (rows - i) / 2, left = (cols - i) / 2;
        const long mass = prefix(top + i, left + i) - prefix(top, left + i) - prefix(top + i, left) + prefix(top, left);
        result.sizes.push_back(i);
        result.mass.push_back(mass);
        if (mass > 0) {
            sizes.push_back(i);
            masses.push_back(static_cast<double>(mass));
        }
    }
    if (sizes.size() < 2)
        throw std::invalid_argument("central_box_mass: " + std::to_string(sizes.size()) +
                                    " centred boxes hold a cell in state " + std::to_string(state) +
                                    ", a fit needs at least 2");
    result.fit = fit_log_log(sizes, masses);
    return result;
}

std::vector<double> power_law(const LineFit& log_fit, std::span<const double> x) {
    std::vector<double> y;
    y.reserve(x.size());
    for (double v : x) y.push_back(std::exp(log_fit.intercept) * std::pow(v, log_fit.slope));
    return y;
}

}  // namespace sim
