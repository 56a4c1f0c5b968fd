#include "sim/diffusion_kernel.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>

#include "sim/check.hpp"
#include "sim/parallel_steps.hpp"

namespace sim {
namespace {

// One row, the halo already in place: up, mid and down point at column 0 of
// the rows above, at and below, whose columns -1 and n hold the wrap copies.
// The arithmetic is sim::Diffusion::step's, operation for operation
// (neighbours summed up, left, right, down from the left; then
// c + r * (neighbours - 4c)), so the double instantiation gives the same bits.
// Each lane of the vector body does the scalar IEEE arithmetic (no FMA:
// -ffp-contract=off), so body and scalar tail agree. target_clones: AVX2
// where the CPU has it, SSE2 otherwise, chosen once at load time (same bits).
template <class Real>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
[[gnu::noinline]] void
diffuse_row(const Real* __restrict up, const Real* __restrict mid, const Real* __restrict down, Real* __restrict next,
            std::ptrdiff_t n, Real r) {
    const Real four = 4;
#ifdef _OPENMP
#pragma omp simd  // vectorize at -O2 too, as in gray_scott_kernels.cpp; no reduction, so same bits
#endif
    for (std::ptrdiff_t j = 0; j < n; ++j) {
        const Real c = mid[j];
        const Real neighbours = up[j] + mid[j - 1] + mid[j + 1] + down[j];
        next[j] = c + r * (neighbours - four * c);
    }
}

}  // namespace

template <class Real>
DiffusionKernel<Real>::DiffusionKernel(const DiffusionParams& params, const Grid<double>& start) : params_(params) {
    params_.validate();
    if (params_.boundary != Boundary::wrap)
        throw std::invalid_argument(std::string("boundary = \"") + to_string(params_.boundary) +
                                    "\" is not allowed: the diffusion kernel runs on the torus, use \"wrap\"");
    require_square_field("field", start, params_.n);
    a_[0] = PaddedField<Real>(params_.n);
    a_[1] = PaddedField<Real>(params_.n);
    a_[0].load(start);
}

template <class Real>
Grid<double> DiffusionKernel<Real>::field() const {
    return a_[current_].extract();
}

template <class Real>
void DiffusionKernel<Real>::step(int steps, int threads) {
    const int n = params_.n;
    const Real r = static_cast<Real>(params_.r);
    const int first = current_;
    parallel_steps(n, steps, threads, [&](int s, int begin, int end) {
        const int from = (first + s) & 1;
        const PaddedRows<Real> a = a_[from].rows(), next = a_[from ^ 1].rows();
        for (int i = begin; i < end; ++i) {
            diffuse_row<Real>(a.row(i - 1), a.row(i), a.row(i + 1), next.row(i), n, r);
            next.wrap_row(i);
        }
    });
    current_ = (first + steps) & 1;
    steps_ += steps;
}

template class DiffusionKernel<float>;
template class DiffusionKernel<double>;

}  // namespace sim
