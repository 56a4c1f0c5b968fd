#pragma once
// The site-percolation threshold of the square lattice by the Newman-Ziff
// algorithm (Newman & Ziff, PRL 85, 4104 (2000); PRE 64, 016706 (2001)).
//
// Each sample fills the L x L torus one site at a time in a random order and
// keeps the clusters in a union-find that also stores, for every site, its
// displacement to its parent. A new bond that joins a cluster to itself closes
// a loop; if the displacements around that loop do not add up to zero, the
// loop goes round the torus and the cluster wraps (horizontally when the x
// part is nonzero, vertically when the y part is). One sample thus gives the
// occupation numbers n_h and n_v at which the torus first wraps each way, at
// a cost of about one find per bond.
//
// Those numbers give R_L(n), the probability of wrapping with exactly n sites
// occupied (the canonical ensemble); the binomial convolution
// R_L(p) = sum_n C(N,n) p^n (1-p)^(N-n) R_L(n) gives it for every p at once,
// and p_c is where R_L(p) crosses its known value at p_c for L = infinity
// (Pinson 1994): there the error falls as L^(-11/4) instead of the L^(-3/4)
// of the mean wrapping point n_c / N.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sim/random.hpp"

namespace sim {

// Which wrapping event R_L(p) counts. The values are R_infinity(p_c) for the
// square lattice (Newman & Ziff 2001, table I, from Pinson's exact results).
enum class WrapCriterion {
    // A cluster wraps in one given direction, horizontal or vertical: the mean
    // of both, so every sample counts twice (R^(h) = 0.521058290). Default:
    // at equal samples its standard error is about 10% below R^(e)'s and 15%
    // below R^(b)'s; at L >= 32 none shows a bias beyond its 4e-5 error bar
    // (at L = 16, 10^6 samples, R^(h) is 1.2e-4 high, R^(e) 1.8e-4, R^(b) 0.7e-4).
    one_direction,
    either_direction,  // a cluster wraps horizontally or vertically (R^(e) = 0.690473725)
    both_directions,   // a cluster wraps horizontally and vertically (R^(b) = 0.351642855)
};
double wrapping_probability_at_threshold(WrapCriterion criterion);

// Occupation numbers (1 = the first site) at which a cluster first wraps
// horizontally and vertically; 0 if it never does.
struct WrappingPoints {
    std::uint32_t horizontal = 0;
    std::uint32_t vertical = 0;
};

// Occupies the sites of the size x size torus (site = row * size + col) in
// the given order, which need not name them all, and says when it first
// wrapped each way (for hand-made lattices in tests). Throws
// std::invalid_argument for a bad size, a site out of range or a repeated site.
WrappingPoints wrapping_points_for_order(int size, std::span<const std::uint32_t> order);

// `samples` independent samples, each occupying sites in a uniform random
// order (Fisher-Yates with rng.below, drawn one site at a time and stopped
// once the torus wraps both ways) until it wraps both ways.
std::vector<WrappingPoints> wrapping_points(int size, int samples, Random& rng);

struct ThresholdEstimate {
    double p_c;             // where R_L(p) = R_infinity(p_c)
    double standard_error;  // one standard deviation of p_c from the sample spread
    int samples;
    int size;
};

// p_c from samples already drawn (size is the L they were drawn at).
ThresholdEstimate threshold_from_wrapping(const std::vector<WrappingPoints>& points, int size,
                                          WrapCriterion criterion = WrapCriterion::one_direction);

// `samples` independent samples at lattice size L, drawing from rng.
ThresholdEstimate newman_ziff_threshold(int size, int samples, Random& rng,
                                        WrapCriterion criterion = WrapCriterion::one_direction);

// The occupation numbers at which the first wrapping cluster (either
// direction) appears, one per sample (for tests); draws as wrapping_points.
std::vector<std::uint32_t> wrapping_occupation(int size, int samples, Random& rng);

// R_L(p) for the given criterion by the binomial convolution (for tests and plots).
double wrapping_probability(const std::vector<WrappingPoints>& points, int size, WrapCriterion criterion,
                            double p);

// R_L(p) at each p of `ps`, the convolution's tables built once: O(N)
// logarithms, then O(sqrt N) a p, where the one-p call pays the O(N) each
// time. What a plotted curve needs; each value is the one-p call's, bit for bit.
std::vector<double> wrapping_probability(const std::vector<WrappingPoints>& points, int size, WrapCriterion criterion,
                                         std::span<const double> ps);

// Where the R(p) curves of two sample sets (of lattice sizes size_a and
// size_b) cross inside [low, high]: the difference is sampled at `steps` + 1
// evenly spaced p, and the crossing taken is the first change of sign between
// its most negative and its most positive samples (the finite-size curves
// cross once near p_c; sample noise can add wiggles in the tails, where both
// are near 0 or 1), then bisected to 1e-12. Empty when the difference does
// not go from one sign to the other there.
std::optional<double> wrapping_crossing(const std::vector<WrappingPoints>& a, int size_a,
                                        const std::vector<WrappingPoints>& b, int size_b, WrapCriterion criterion,
                                        double low, double high, int steps = 200);

// The finite-size extrapolation: p_c(L) = p_c + slope * L^(-11/4), the
// correction of the estimates at R_L(p) = R_infinity(p_c) (Newman & Ziff
// 2000: 2 + 1/nu with nu = 4/3), fitted by weighted least squares, each
// estimate weighted by 1 / standard_error^2. p_c is the intercept.
struct ThresholdExtrapolation {
    double p_c;              // the intercept: p_c at L = infinity
    double standard_error;   // of the intercept, from the estimates' standard errors
    double slope;            // of p_c(L) against L^(-11/4)
    double slope_error;      // its standard error
    double chi_squared;      // of the estimates about the line
    int degrees_of_freedom;  // estimates - 2
};
inline constexpr double threshold_correction_exponent = 11.0 / 4.0;

// Throws std::invalid_argument for fewer than two estimates, two of the same
// size, or a standard error that is not finite and above 0.
ThresholdExtrapolation extrapolate_threshold(std::span<const ThresholdEstimate> estimates);

}  // namespace sim
