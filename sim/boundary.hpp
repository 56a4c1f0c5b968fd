#pragma once
// What lies beyond the edge of a lattice.

#include <string>
#include <utility>
#include <vector>

namespace sim {

enum class Boundary {
    zero,  // cells outside the grid read as 0 (scipy's correlate2d default, the book's choice)
    wrap,  // periodic: the grid is a torus
};

// Each boundary by the name a description gives it.
inline std::vector<std::pair<std::string, Boundary>> boundary_names() {
    return {{"zero", Boundary::zero}, {"wrap", Boundary::wrap}};
}

inline const char* to_string(Boundary b) {
    return b == Boundary::zero ? "zero" : "wrap";
}

}  // namespace sim
