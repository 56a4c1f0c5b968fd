#include "sim/diffusion.hpp"

#include <numeric>
#include <stdexcept>
#include <string>

#include "sim/check.hpp"

namespace sim {

void DiffusionParams::validate() const {
    require_integer("n", n, 1, 8192);
    require_number("r", r, 0.0, 0.25, "the explicit 5-point update's stability bound; beyond it the checkerboard grows");
    require_integer("block_size", block_size, 0, n);
    require_integer("block_row", block_row, 0, n - block_size);
    require_integer("block_col", block_col, 0, n - block_size);
    require_number("block_value", block_value, -1e12, 1e12);
}

Diffusion::Diffusion(const DiffusionParams& params) : params_(params) {
    params_.validate();
    a_ = Grid<double>(params_.n, params_.n, 0.0);
    next_ = a_;
    for (int i = 0; i < params_.block_size; ++i)
        for (int j = 0; j < params_.block_size; ++j) a_(params_.block_row + i, params_.block_col + j) = params_.block_value;
}

Diffusion::Diffusion(const DiffusionParams& params, Grid<double> initial) : params_(params) {
    params_.validate();
    require_square_field("field", initial, params_.n);
    a_ = std::move(initial);
    next_ = a_;
}

void Diffusion::step() {
    const int n = params_.n;
    const bool wrap = params_.boundary == Boundary::wrap;
    // Neighbour value, reading 0 (zero-fill) or the opposite edge (wrap) off the grid.
    auto at = [&](int i, int j) -> double {
        if (wrap) return a_((i + n) % n, (j + n) % n);
        return (i < 0 || i >= n || j < 0 || j >= n) ? 0.0 : a_(i, j);
    };
    for (int i = 0; i < n; ++i) {
        const bool edge_row = i == 0 || i == n - 1;
        for (int j = 0; j < n; ++j) {
            const double c = a_(i, j);
            double neighbours;
            if (edge_row || j == 0 || j == n - 1)
                neighbours = at(i - 1, j) + at(i, j - 1) + at(i, j + 1) + at(i + 1, j);
            else  // interior fast path, same order of additions
                neighbours = a_(i - 1, j) + a_(i, j - 1) + a_(i, j + 1) + a_(i + 1, j);
            next_(i, j) = c + params_.r * (neighbours - 4.0 * c);
        }
    }
    std::swap(a_, next_);
    ++steps_;
}

double Diffusion::total() const { return std::accumulate(a_.cells().begin(), a_.cells().end(), 0.0); }

}  // namespace sim
