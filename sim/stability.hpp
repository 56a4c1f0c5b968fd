#pragma once
// Where an explicit diffusion update a' = a + r * correlate(a, K) stops being
// stable, in theory and by experiment. With wrap, the update multiplies the
// Fourier mode of wave numbers (x, y) by 1 + r * S(x, y), where S is the
// kernel's symbol; it is stable while |1 + r S| <= 1 for every mode, that is
// r <= 2 / -min S. The 5-point kernel has min S = -8 at the checkerboard
// (bound 1/4), the book's 9-point Gray-Scott kernel -1.6 (bound 1.25).

#include <array>

namespace sim {

using Kernel3 = std::array<double, 9>;  // row-major 3 x 3 weights, centre at index 4

// min over the n x n torus's wave numbers of the kernel's symbol S.
double symbol_minimum(const Kernel3& kernel, int n);
// 2 / -min S: the largest stable r.
double stability_bound(const Kernel3& kernel, int n);

// Runs the update, unchecked, for `steps` steps on an n x n torus from a
// checkerboard plus a smooth wave, and returns max |a| at the end over max |a|
// at the start: above 1 the update amplifies something.
double amplification(const Kernel3& kernel, double r, int n, int steps);

// The smallest r in first, first + step, ... at which amplification exceeds
// 1 + 1e-9: the stability bound found by a sweep.
double empirical_bound(const Kernel3& kernel, double first, double step, int n, int steps);

}  // namespace sim
