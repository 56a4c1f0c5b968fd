#include "sim/check.hpp"
#include "sim/gray_scott_kernels.hpp"

#include <cstddef>
#include <optional>
#include <type_traits>

#include "sim/parallel_steps.hpp"

namespace sim {
namespace {

template <class Real>
struct Rates {
    Real ra, rb, f, fk;  // fk = f + k, rounded once from the double sum (as sim::GrayScott's)
};

// One row of both fields, the halo already in place: a_up, a_mid, a_down
// (and b_*) point at column 0 of the rows above, at and below, whose columns
// -1 and n hold the wrap copies. The arithmetic is sim::GrayScott's, operation
// for operation (laplacian with opposite neighbours paired, then the book's
// order), so the double instantiation gives the same bits. GCC vectorizes the
// loop (-fopt-info-vec: "loop vectorized using 32 byte vectors" in the AVX2
// clone, 16 byte in the default SSE2 one); each lane does the scalar IEEE
// arithmetic (no FMA: -ffp-contract=off), so the vector body and the scalar
// tail agree. target_clones: the binary runs on any x86-64 and uses AVX2
// where the CPU has it, chosen once at load time (same bits either way).
template <class Real>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
[[gnu::noinline]] void
update_row(const Real* __restrict a_up, const Real* __restrict a_mid, const Real* __restrict a_down,
           const Real* __restrict b_up, const Real* __restrict b_mid, const Real* __restrict b_down,
           Real* __restrict next_a, Real* __restrict next_b, std::ptrdiff_t n, Rates<Real> c) {
    const Real corner = static_cast<Real>(0.05), edge = static_cast<Real>(0.2), one = 1;
#ifdef _OPENMP
#pragma omp simd  // vectorize at -O2 too (GCC 12's -O2 cost model skips this loop); no reduction, so same bits
#endif
    for (std::ptrdiff_t j = 0; j < n; ++j) {
        const std::ptrdiff_t l = j - 1, r = j + 1;
        const Real a_corners = (a_up[l] + a_down[r]) + (a_up[r] + a_down[l]);
        const Real a_edges = (a_up[j] + a_down[j]) + (a_mid[l] + a_mid[r]);
        const Real ca = corner * a_corners + edge * a_edges - a_mid[j];
        const Real b_corners = (b_up[l] + b_down[r]) + (b_up[r] + b_down[l]);
        const Real b_edges = (b_up[j] + b_down[j]) + (b_mid[l] + b_mid[r]);
        const Real cb = corner * b_corners + edge * b_edges - b_mid[j];
        const Real old_a = a_mid[j], old_b = b_mid[j];
        const Real reaction = old_a * (old_b * old_b);
        next_a[j] = old_a + ((c.ra * ca - reaction) + c.f * (one - old_a));
        next_b[j] = old_b + ((c.rb * cb + reaction) - c.fk * old_b);
    }
}

}  // namespace

template <class Real>
GrayScottKernel<Real>::GrayScottKernel(const GrayScottParams& params, const Grid<double>& a, const Grid<double>& b)
    : params_(params) {
    params_.validate();
    require_square_field("A", a, params_.n);
    require_square_field("B", b, params_.n);
    for (PaddedField<Real>* field : {&a_[0], &a_[1], &b_[0], &b_[1]}) *field = PaddedField<Real>(params_.n);
    a_[0].load(a);
    b_[0].load(b);
}

template <class Real>
Grid<double> GrayScottKernel<Real>::a() const {
    return a_[current_].extract();
}

template <class Real>
Grid<double> GrayScottKernel<Real>::b() const {
    return b_[current_].extract();
}

template <class Real>
void GrayScottKernel<Real>::step(int steps, int threads) {
    const int n = params_.n;
    const Rates<Real> rates{static_cast<Real>(params_.ra), static_cast<Real>(params_.rb), static_cast<Real>(params_.f),
                            static_cast<Real>(params_.f + params_.k)};
    const int first = current_;
    parallel_steps(n, steps, threads, [&](int s, int begin, int end) {
        // float flushes subnormals (see SubnormalsFlushed); double keeps
        // gradual underflow, so that it stays equal to sim::GrayScott.
        std::optional<SubnormalsFlushed> flushed;
        if constexpr (std::is_same_v<Real, float>) flushed.emplace();
        const int from = (first + s) & 1, to = from ^ 1;
        const PaddedRows<Real> a = a_[from].rows(), b = b_[from].rows(), next_a = a_[to].rows(), next_b = b_[to].rows();
        for (int i = begin; i < end; ++i) {
            update_row<Real>(a.row(i - 1), a.row(i), a.row(i + 1), b.row(i - 1), b.row(i), b.row(i + 1), next_a.row(i),
                             next_b.row(i), n, rates);
            next_a.wrap_row(i);
            next_b.wrap_row(i);
        }
    });
    current_ = (first + steps) & 1;
    steps_ += steps;
}

template class GrayScottKernel<float>;
template class GrayScottKernel<double>;

}  // namespace sim
