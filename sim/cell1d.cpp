#include "sim/cell1d.hpp"

#include <stdexcept>
#include <string>

#include "sim/check.hpp"

namespace sim {

void Cell1DParams::validate() const {
    require_integer("rule", rule, 0, 255);
    require_integer("rows", rows, 1, 100000);
    if (width != 0) require_integer("width", width, 1, 200001);
}

Cell1D::Cell1D(const Cell1DParams& params) : params_(params) {
    params_.validate();
    if (params_.width == 0) params_.width = 2 * params_.rows + 1;
    cells_ = Grid<std::uint8_t>(params_.rows, params_.width, 0);
    cells_(0, params_.width / 2) = 1;
}

void Cell1D::step() {
    if (rows_filled_ == params_.rows)
        throw std::logic_error("Cell1D::step: all " + std::to_string(params_.rows) + " rows are filled");
    const int m = params_.width;
    const int rule = params_.rule;
    const std::uint8_t* prev = cells_.data() + static_cast<std::size_t>(rows_filled_ - 1) * m;
    std::uint8_t* row = cells_.data() + static_cast<std::size_t>(rows_filled_) * m;
    long on = 0;
    auto set = [&](int j, int left, int right) {
        row[j] = static_cast<std::uint8_t>((rule >> (4 * left + 2 * prev[j] + right)) & 1);
        on += row[j];
    };
    const bool wrap = params_.boundary == Boundary::wrap;
    // The end cells read 0 beyond the row, or the other end when wrapping
    // (with one cell, that cell is both its own neighbours).
    const int left_of_first = wrap ? prev[m - 1] : 0;
    const int right_of_last = wrap ? prev[0] : 0;
    if (m == 1) {
        set(0, left_of_first, right_of_last);
    } else {
        set(0, left_of_first, prev[1]);
        for (int j = 1; j < m - 1; ++j) set(j, prev[j - 1], prev[j + 1]);
        set(m - 1, prev[m - 2], right_of_last);
    }
    on_cells_ += on;
    ++rows_filled_;
}

std::vector<long> count_cells(int rule, int n, Boundary boundary) {
    Cell1D ca(Cell1DParams{rule, n, 0, boundary});
    std::vector<long> counts;
    counts.reserve(n > 1 ? static_cast<std::size_t>(n - 1) : 0);
    for (int i = 1; i < n; ++i) {
        counts.push_back(ca.on_cells());
        ca.step();
    }
    return counts;
}

}  // namespace sim
