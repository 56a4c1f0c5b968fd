#pragma once
// A 2-D array of cells stored row by row: the state of every lattice model.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace sim {

template <class T>
class Grid {
public:
    Grid() = default;
    Grid(int rows, int cols, T fill = T{}) : rows_(rows), cols_(cols) {
        if (rows < 0 || cols < 0)
            throw std::invalid_argument("grid size " + std::to_string(rows) + "x" + std::to_string(cols) +
                                        " is negative");
        cells_.assign(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols), fill);
    }

    int rows() const { return rows_; }
    int cols() const { return cols_; }
    std::size_t size() const { return cells_.size(); }

    T& operator()(int row, int col) { return cells_[index(row, col)]; }
    const T& operator()(int row, int col) const { return cells_[index(row, col)]; }

    T* data() { return cells_.data(); }
    const T* data() const { return cells_.data(); }
    const std::vector<T>& cells() const { return cells_; }
    void fill(T value) { cells_.assign(cells_.size(), value); }

    bool operator==(const Grid&) const = default;

private:
    std::size_t index(int row, int col) const {
        return static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(col);
    }
    int rows_ = 0;
    int cols_ = 0;
    std::vector<T> cells_;
};

}  // namespace sim
