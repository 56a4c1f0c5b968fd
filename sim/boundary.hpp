#pragma once
// What lies beyond the edge of a lattice.

#include <string>
#include <string_view>

namespace sim {

enum class Boundary {
    zero,  // cells outside the grid read as 0 (scipy's correlate2d default, the book's choice)
    wrap,  // periodic: the grid is a torus
};

inline const char* to_string(Boundary b) { return b == Boundary::zero ? "zero" : "wrap"; }

// "zero" or "wrap"; throws std::invalid_argument naming what is allowed.
Boundary parse_boundary(std::string_view text);

}  // namespace sim
