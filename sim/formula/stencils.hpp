#pragma once
// Ready's stencils, as data: its src/readybase/stencils.cpp, in 1, 2 and 3
// dimensions at each accuracy. A formula names one as `label_X` for a
// chemical X (laplacian_a, x_gradient_b); sim/formula/lower.cpp turns it
// into the weighted sum Ready writes for it, in its order of operations.

#include <string>
#include <vector>

#include "sim/formula/rule.hpp"

namespace sim::formula {

// A point of a stencil: its offset from the cell (x east, y north, z up)
// and its integer weight.
struct StencilPoint {
    int x, y, z, weight;
};

struct Stencil {
    std::string label;
    std::vector<StencilPoint> points;  // in Ready's order: planes down to up, rows north to south, columns west to east
    int divisor = 1;   // the sum is divided by divisor * dx^dx_power
    int dx_power = 0;
};

// Ready's stencils for a grid of `dimensions` (1, 2 or 3) at `accuracy`:
// x_, y_ and z_ gradient, deriv2 and deriv3, gaussian, laplacian,
// bilaplacian, trilaplacian and the eight sobel stencils, in Ready's order.
// Throws std::invalid_argument for another number of dimensions.
std::vector<Stencil> ready_stencils(Accuracy accuracy, int dimensions);

// The stencil keywords, as in Ready: `label_X` for a chemical X (the same
// labels in every dimension), and gradient_mag_squared.
const std::vector<std::string>& stencil_names();

}  // namespace sim::formula
