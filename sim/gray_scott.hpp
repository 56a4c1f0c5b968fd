#pragma once
// The Gray-Scott reaction-diffusion model (Think Complexity 2e, section 7.2):
// two chemicals A and B on a torus, updated together from the old state:
//     cA = correlate(A, K), cB = correlate(B, K),  K = [[.05, .2, .05],
//                                                       [.2,  -1, .2 ],
//                                                       [.05, .2, .05]]
//     reaction = A * B^2
//     A += ra * cA - reaction + f * (1 - A)      (A is fed at rate f)
//     B += rb * cB + reaction - (f + k) * B      (B is removed at rate f + k)
//
// Stability of the diffusion part, a' = a + r * correlate(a, K): it equals
//     a' = (1 - r) * a + r * (.05 * corners + .2 * edges),
// whose nine weights sum to 1 and are all >= 0 exactly when 0 <= r <= 1.
// Then every new value is a weighted mean of old ones: no new extremes, no
// oscillation (monotone). Von Neumann analysis gives K the symbol
// .4 (cos x + cos y) + .2 cos x cos y - 1, from 0 down to -1.6 (the
// checkerboard), so the L2 limit is r <= 2 / 1.6 = 1.25; between 1 and 1.25
// the checkerboard flips sign every step and concentrations turn negative.
// validate() therefore allows ra, rb in [0, 1]; the book's 0.5 and 0.25 sit
// well inside.

#include "sim/grid.hpp"
#include "sim/random.hpp"

namespace sim {

struct GrayScottParams {
    int n = 100;         // grid is n x n cells, wrapped into a torus, 3..4096
    double ra = 0.5;     // diffusion rate of A, 0..1 (see the stability note)
    double rb = 0.25;    // diffusion rate of B, 0..1
    double f = 0.035;    // feed rate of A (and part of B's removal), 0..0.2
    double k = 0.057;    // extra removal rate of B, 0..0.2
    double noise = 0.1;  // B starts uniform in [0, noise), 0..1
    double island = 0.1; // added to B on the central 2r x 2r square, r = n / 20, 0..1

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class GrayScott {
public:
    // A = 1 everywhere; B = noise * rng.uniform(), drawn row by row; then the
    // book's add_island: B += island on rows and columns [n/2 - r, n/2 + r).
    GrayScott(const GrayScottParams& params, Random& rng);
    // Starts from the given n x n fields instead (for tests).
    GrayScott(const GrayScottParams& params, Grid<double> a, Grid<double> b);

    void step();
    const Grid<double>& a() const { return a_; }
    const Grid<double>& b() const { return b_; }
    int steps() const { return steps_; }               // steps taken so far
    const GrayScottParams& params() const { return params_; }

private:
    GrayScottParams params_;
    Grid<double> a_, b_;
    Grid<double> next_a_, next_b_;  // written by step(), then swapped in
    int steps_ = 0;
};

}  // namespace sim
