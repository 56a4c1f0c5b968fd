#pragma once
// Fast Gray-Scott kernels: the model of sim/gray_scott.hpp (same update, same
// 9-point kernel with wrap) in float or double, vectorized and threaded with
// OpenMP, for throughput (the figures keep using sim::GrayScott).
//
// Layout: each field lives in a padded buffer (sim/padded_field.hpp: a
// one-cell halo of wrap copies around 64-byte-aligned rows). Two buffers per
// field (double buffering): a step reads the old pair and writes the new pair,
// including the new pair's halo, which the thread that wrote a row fills right
// after it (no extra barrier).
//
// Reproducibility: every cell is computed from the old state only, with the
// same operations in the same order whatever the thread count, the vector
// width (SSE2, AVX2 or AVX-512, picked at load time) or the row's split into
// vector body and scalar tail; the project builds with -ffp-contract=off, so no FMA.
// Results are therefore identical for any number of threads, and the double
// kernel equals sim::GrayScott bit for bit (same order of additions). The
// float kernel flushes subnormals to zero (values below 1.2e-38 count as 0;
// sim/parallel_steps.hpp says why), the double one does not.

#include "sim/gray_scott.hpp"
#include "sim/grid.hpp"
#include "sim/padded_field.hpp"

namespace sim {

template <class Real>
class GrayScottKernel {
public:
    // Copies the start state (n x n each, finite); validates params.
    GrayScottKernel(const GrayScottParams& params, const Grid<double>& a, const Grid<double>& b);

    // Starts again from a new state (n x n each, finite) with new params, as
    // if newly constructed (steps() is 0), in the same buffers when n is
    // unchanged: a run of many short runs (gs-atlas) maps its pages once.
    void restart(const GrayScottParams& params, const Grid<double>& a, const Grid<double>& b);

    // Advances `steps` steps (>= 0) on `threads` OpenMP threads (0: OpenMP's
    // default; > 0: exactly that many). The result does not depend on threads.
    void step(int steps = 1, int threads = 0);

    Grid<double> a() const;  // the current fields, converted to double
    Grid<double> b() const;
    Grid<Real> b_as_stored() const;  // B as the kernel holds it: no rounding, half the memory in float

    // Exact tests of the current state, read in place (no copy). B is +0
    // everywhere (-0 does not count): then B stays +0 at every later step,
    // whatever A is, as long as A stays finite.
    bool b_is_zero() const { return b_[current_].all_positive_zero(); }
    // The last step left every cell of A and B with the same bits: the state
    // is a fixed point of the step, which is a function of the state alone,
    // so every later step gives these bits again. False before any step.
    bool unchanged() const;
    // Every cell of A and B is finite and within `bound` of 0 (the test of
    // sim::require_finite, without converting the fields).
    bool within(double bound) const { return a_[current_].within(bound) && b_[current_].within(bound); }
    int steps() const { return steps_; }
    const GrayScottParams& params() const { return params_; }

private:
    GrayScottParams params_;
    PaddedField<Real> a_[2], b_[2];
    int current_ = 0;  // which of the pairs holds the state
    int steps_ = 0;
};

// The vector code the float kernel's rows run on this CPU: "avx512f" (an
// AVX-512 row written with intrinsics) or "target_clones" (the portable row,
// compiled for AVX-512, AVX2 and SSE2, the widest picked at load time).
const char* float_kernel_vectors();

extern template class GrayScottKernel<float>;
extern template class GrayScottKernel<double>;

}  // namespace sim
