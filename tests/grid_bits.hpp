#pragma once
// Whether two grids hold the same bits, cell by cell (a negative zero is
// not a zero, a NaN is itself): the check of every "the same bits on any
// number of threads" test.
#include <cstring>

#include "sim/grid.hpp"

inline bool same_bits(const sim::Grid<double>& a, const sim::Grid<double>& b) {
    if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
    for (int y = 0; y < a.rows(); ++y)
        for (int x = 0; x < a.cols(); ++x)
            if (std::memcmp(&a(y, x), &b(y, x), sizeof(double)) != 0) return false;
    return true;
}
