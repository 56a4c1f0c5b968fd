#include "sim/percolation.hpp"

#include <algorithm>

#include <stdexcept>
#include <string>
#include <utility>

#include "sim/check.hpp"

namespace sim {

void PercolationParams::validate() const {
    require_integer("n", n, 1, 8192);
    require_number("q", q, 0.0, 1.0);
}

Percolation::Percolation(const PercolationParams& params, Random& rng) {
    params.validate();
    cells_ = Grid<std::uint8_t>(params.n, params.n, blocked);
    // Every cell draws, the top row too, so the stream matches the book's
    // n x n np.random.choice before array[0] = 5 overwrites the top row.
    for (int i = 0; i < params.n; ++i)
        for (int j = 0; j < params.n; ++j) cells_(i, j) = rng.uniform() < params.q ? porous : blocked;
    for (int j = 0; j < params.n; ++j) cells_(0, j) = wet;
    start();
}

Percolation::Percolation(Grid<std::uint8_t> cells) : cells_(std::move(cells)) {
    if (cells_.rows() < 1 || cells_.cols() < 1) throw std::invalid_argument("percolation grid is empty");
    for (std::uint8_t c : cells_.cells())
        if (c != blocked && c != porous && c != wet)
            throw std::invalid_argument("percolation cell = " + std::to_string(c) +
                                        " is not allowed: cells must be 0 (blocked), 1 (porous) or 5 (wet)");
    start();
}

void Percolation::start() {
    const int rows = cells_.rows(), cols = cells_.cols();
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j)
            if (cells_(i, j) == wet) {
                front_.push_back(i * cols + j);
                ++wet_count_;
                if (i == rows - 1) ++bottom_wet_;
            }
}

// Only a neighbour of a cell wetted by the previous step can become wet now:
// a porous cell next to an older wet cell was wetted the step after that
// cell. So scanning the front gives exactly the synchronous rule. Marking
// cells wet during the scan is safe because only the old front is scanned.
long Percolation::step() {
    const int rows = cells_.rows(), cols = cells_.cols();
    std::uint8_t* c = cells_.data();
    next_front_.clear();
    auto wet_if_porous = [&](int index) {
        if (c[index] != porous) return;
        c[index] = wet;
        next_front_.push_back(index);
    };
    for (const int index : front_) {
        const int i = index / cols, j = index % cols;
        if (i > 0) wet_if_porous(index - cols);
        if (i < rows - 1) wet_if_porous(index + cols);
        if (j > 0) wet_if_porous(index - 1);
        if (j < cols - 1) wet_if_porous(index + 1);
    }
    const int bottom_start = (rows - 1) * cols;
    for (const int index : next_front_)
        if (index >= bottom_start) ++bottom_wet_;
    std::swap(front_, next_front_);
    const long wetted = static_cast<long>(front_.size());
    wet_count_ += wetted;
    ++steps_;
    return wetted;
}

PercolationRun run_to_bottom_or_fixed_point(Percolation& model) {
    long num_wet = model.wet_count();
    for (int steps = 1;; ++steps) {
        model.step();
        if (model.bottom_row_wet()) return {true, PercolationStop::bottom_row_wet, steps};
        const long new_num_wet = model.wet_count();
        if (new_num_wet == num_wet) return {false, PercolationStop::fixed_point, steps};
        num_wet = new_num_wet;
    }
}

PercolationRun run_to_fixed_point(Percolation& model) {
    for (int steps = 1;; ++steps)
        if (model.step() == 0) return {model.bottom_row_wet(), PercolationStop::fixed_point, steps};
}

std::vector<double> find_critical(int n, double start, double step, int iterations, Random& rng) {
    std::vector<double> walk{start};
    double q = start;
    for (int i = 0; i < iterations; ++i) {
        PercolationParams p;
        p.n = n;
        p.q = std::clamp(q, 0.0, 1.0);
        Percolation model(p, rng);
        // A percolating run says q is probably above critical: step down; else up.
        q += run_to_bottom_or_fixed_point(model).percolates ? -step : step;
        walk.push_back(q);
    }
    return walk;
}

}  // namespace sim
