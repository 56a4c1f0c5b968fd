#pragma once
// Fast diffusion kernel: the model of sim/diffusion.hpp with wrap (the
// explicit 5-point update on the torus) in float or double, vectorized and
// threaded with OpenMP, for throughput and for comparing float32 with float64
// against the exact Fourier solution (the figures keep using sim::Diffusion).
//
// Layout and threading are those of sim/gray_scott_kernels.hpp: the field lives
// in two padded buffers (sim/padded_field.hpp, one-cell halo of wrap copies,
// 64-byte-aligned rows); a step reads one and writes the other, halo included,
// its rows split among OpenMP threads (sim/parallel_steps.hpp).
//
// Reproducibility: every cell is computed from the old state only, with the
// same operations in the same order whatever the thread count, the vector
// width or the row's split into vector body and scalar tail, and no FMA
// (-ffp-contract=off). Results are therefore identical for any number of
// threads, and the double kernel equals sim::Diffusion (wrap) bit for bit.

#include "sim/diffusion.hpp"
#include "sim/grid.hpp"
#include "sim/padded_field.hpp"

namespace sim {

template <class Real>
class DiffusionKernel {
public:
    // Copies the start field (n x n, finite); validates params and requires
    // boundary == wrap (the halo holds wrap copies; zero-fill is not done here).
    DiffusionKernel(const DiffusionParams& params, const Grid<double>& start);

    // Advances `steps` steps (>= 0) on `threads` OpenMP threads (0: OpenMP's
    // default; > 0: exactly that many). The result does not depend on threads.
    void step(int steps = 1, int threads = 0);

    Grid<double> field() const;  // the current field, converted to double
    int steps() const { return steps_; }
    const DiffusionParams& params() const { return params_; }

private:
    DiffusionParams params_;
    PaddedField<Real> a_[2];
    int current_ = 0;  // which buffer holds the state
    int steps_ = 0;
};

extern template class DiffusionKernel<float>;
extern template class DiffusionKernel<double>;

}  // namespace sim
