#pragma once
// The explicit stability bound on a formula's timestep, from what its
// deltas do to their neighbours (its stencil terms, whatever expression is
// around them), for the rule's integrator.
//
// The formula is linearised about a uniform state: in double, on a
// periodic grid of 8 cells a side, one cell of chemical c is raised by a
// small amount and the change of delta_c everywhere is its impulse
// response h_c (the stencils reach at most 3 cells, so 8 hold it whole).
// Its symbol sigma_c(theta) = sum_x h_c(x) exp(-i theta . x), less
// sigma_c(0) (what the reaction does to a uniform state, which no stencil
// sees), is the rate at which the grid's Fourier mode theta grows; the
// step multiplies it by R(timestep * rate), R = 1 + z for forward Euler,
// 1 + z + z^2/2 for Heun, the fourth-order Taylor polynomial for RK4. The
// bound is the largest timestep with |R| <= 1 for every mode (sampled
// finely along each axis) and chemical. For D * laplacian_a at medium
// accuracy in 2-D (dx = 1) the rate at theta = (pi, pi) is -32/6 D, and
// Euler's bound 0.375 / D.

#include <limits>
#include <string>
#include <vector>

#include "sim/formula/rule.hpp"

namespace sim::formula {

struct StabilityBound {
    // The largest stable timestep: infinity where the deltas read no
    // neighbour (no bound from the stencils), 0 where no timestep is
    // stable (an advection term under forward Euler).
    double timestep = std::numeric_limits<double>::infinity();
    std::string chemical;         // whose stencil terms set it
    std::vector<double> theta;    // the mode that sets it, per axis
    double rate_real = 0, rate_imaginary = 0;  // sigma(theta) - sigma(0) there
    // Three chemicals or more whose stencil terms reach into each other:
    // the bound is from each one's own terms only.
    bool coupled = false;
};

// The bound for `rule` (its integrator and accuracy) on a grid of
// `dimensions`, linearised about `base` (one value per chemical: the start's
// mean). Throws what compiling the rule throws.
StabilityBound stability_bound(const Rule& rule, int dimensions, const std::vector<double>& base);

}  // namespace sim::formula
