#include "sim/forest_fire.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "sim/check.hpp"

namespace sim {

void ForestFireParams::validate() const {
    require_integer("n", n, 3, 8192);  // 3 keeps a cell's four neighbours distinct on the torus
    require_number("p", p, 0.0, 1.0);
    require_number("f", f, 0.0, 1.0);
    require_number("initial_density", initial_density, 0.0, 1.0);
}

ForestFire::ForestFire(const ForestFireParams& params, std::uint64_t seed) : params_(params), rng_(seed) {
    params_.validate();
    cells_ = Grid<std::uint8_t>(params_.n, params_.n, empty);
    for (int i = 0; i < params_.n; ++i)
        for (int j = 0; j < params_.n; ++j) cells_(i, j) = rng_.uniform() < params_.initial_density ? tree : empty;
    next_ = cells_;
    count();
}

ForestFire::ForestFire(const ForestFireParams& params, Grid<std::uint8_t> cells, std::uint64_t seed)
    : params_(params), rng_(seed), cells_(std::move(cells)) {
    params_.validate();
    if (cells_.rows() != params_.n || cells_.cols() != params_.n)
        throw std::invalid_argument("initial forest is " + std::to_string(cells_.rows()) + "x" +
                                    std::to_string(cells_.cols()) + ", not n x n = " + std::to_string(params_.n) +
                                    "x" + std::to_string(params_.n));
    for (std::uint8_t c : cells_.cells())
        if (c != empty && c != tree && c != fire)
            throw std::invalid_argument("forest cell = " + std::to_string(c) +
                                        " is not allowed: cells must be 0 (empty), 1 (tree) or 5 (fire)");
    next_ = cells_;
    count();
}

void ForestFire::count() {
    trees_ = fires_ = 0;
    for (std::uint8_t c : cells_.cells()) {
        trees_ += c == tree;
        fires_ += c == fire;
    }
}

void ForestFire::step() {
    const int n = params_.n;
    const std::uint8_t* old = cells_.data();
    std::uint8_t* now = next_.data();
    long trees = 0, fires = 0;
    for (int i = 0; i < n; ++i) {
        const int up = (i == 0 ? n - 1 : i - 1) * n, mid = i * n, down = (i == n - 1 ? 0 : i + 1) * n;
        for (int j = 0; j < n; ++j) {
            const double u = rng_.uniform();  // drawn for every cell, see the header
            const int left = j == 0 ? n - 1 : j - 1, right = j == n - 1 ? 0 : j + 1;
            std::uint8_t next_state = empty;
            switch (old[mid + j]) {
            case empty:
                next_state = u < params_.p ? tree : empty;
                break;
            case tree: {
                const bool neighbour_burns = old[up + j] == fire || old[down + j] == fire ||
                                             old[mid + left] == fire || old[mid + right] == fire;
                next_state = neighbour_burns || u < params_.f ? fire : tree;
                break;
            }
            default:  // fire burns out
                next_state = empty;
            }
            now[mid + j] = next_state;
            trees += next_state == tree;
            fires += next_state == fire;
        }
    }
    std::swap(cells_, next_);
    trees_ = trees;
    fires_ = fires;
    ++steps_;
}

}  // namespace sim
