#include "sim/check.hpp"
#include "sim/gray_scott_kernels.hpp"

#include <cstddef>
#include <optional>
#include <type_traits>

#include "sim/parallel_steps.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FIGGEN_GS_AVX512 1
#include <immintrin.h>
#endif

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
// loop (-fopt-info-vec: 64-byte vectors in the AVX-512 clone, 32 in the AVX2
// one, 16 in the default SSE2 one); each lane does the scalar IEEE arithmetic
// (no FMA: -ffp-contract=off), so the vector body and the scalar tail agree.
// target_clones: the binary runs on any x86-64 and uses the widest vectors
// the CPU has, chosen once at load time (same bits either way). The float
// kernel runs update_row_avx512 (below) instead where it can.
template <class Real>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx512f", "avx2", "default")))
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

template <class Real>
using RowUpdate = void (*)(const Real*, const Real*, const Real*, const Real*, const Real*, const Real*, Real*, Real*,
                           std::ptrdiff_t, Rates<Real>);

#ifdef FIGGEN_GS_AVX512
#pragma GCC push_options
#pragma GCC target("avx512f")

// Columns j - 1, j and j + 1 of a row, 16 cells each.
struct Columns {
    __m512 left, here, right;
};

// One row read block by block (j = 0, 16, 32, ...; column j is 64-byte
// aligned). Why not three unaligned loads, as update_row's AVX-512 clone
// does: an unaligned 64-byte load always spans two cache lines, costing two
// of the core's loads; the clone's 12 such loads a block, not its 33 flops,
// bound it (measured with the rows in L1: 3.1 G cells/s, 5.7 G/s if every
// load were aligned). Here the left columns are the block before, kept in a
// register, shifted one lane (valignd); only the right ones load unaligned.
struct RowStream {
    const float* row;
    __m512 before;  // columns j - 16 .. j - 1

    explicit RowStream(const float* r) : row(r), before(_mm512_load_ps(r - 16)) {}
    Columns at(std::ptrdiff_t j) {
        const __m512 here = _mm512_load_ps(row + j);
        // The masked form with every lane set is the same valignd; the plain
        // one trips GCC 12's -Wmaybe-uninitialized in its own header.
        const __m512i here_bits = _mm512_castps_si512(here);
        const __m512i shifted =
            _mm512_mask_alignr_epi32(here_bits, __mmask16(0xFFFF), here_bits, _mm512_castps_si512(before), 15);
        before = here;
        return {_mm512_castsi512_ps(shifted), here, _mm512_loadu_ps(row + j + 1)};
    }
};

// update_row's laplacian, the same operations in the same order.
inline __m512 laplacian(const Columns& up, const Columns& mid, const Columns& down) {
    const __m512 corners = _mm512_add_ps(_mm512_add_ps(up.left, down.right), _mm512_add_ps(up.right, down.left));
    const __m512 edges = _mm512_add_ps(_mm512_add_ps(up.here, down.here), _mm512_add_ps(mid.left, mid.right));
    const __m512 weighted = _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(0.05f), corners),
                                          _mm512_mul_ps(_mm512_set1_ps(0.2f), edges));
    return _mm512_sub_ps(weighted, mid.here);
}

// update_row for float with AVX-512 intrinsics: 16-cell blocks, then
// update_row itself for the last n % 16 cells. Each lane does update_row's
// arithmetic in its order (no FMA), so the bits are the same.
void update_row_avx512(const float* a_up, const float* a_mid, const float* a_down, const float* b_up,
                       const float* b_mid, const float* b_down, float* next_a, float* next_b, std::ptrdiff_t n,
                       Rates<float> c) {
    RowStream au(a_up), am(a_mid), ad(a_down), bu(b_up), bm(b_mid), bd(b_down);
    const __m512 ra = _mm512_set1_ps(c.ra), rb = _mm512_set1_ps(c.rb), f = _mm512_set1_ps(c.f),
                 fk = _mm512_set1_ps(c.fk), one = _mm512_set1_ps(1.0f);
    std::ptrdiff_t j = 0;
    for (; j + 16 <= n; j += 16) {
        const Columns a_mid_j = am.at(j), b_mid_j = bm.at(j);
        const __m512 ca = laplacian(au.at(j), a_mid_j, ad.at(j)), cb = laplacian(bu.at(j), b_mid_j, bd.at(j));
        const __m512 old_a = a_mid_j.here, old_b = b_mid_j.here;
        const __m512 reaction = _mm512_mul_ps(old_a, _mm512_mul_ps(old_b, old_b));
        const __m512 da = _mm512_add_ps(_mm512_sub_ps(_mm512_mul_ps(ra, ca), reaction),
                                        _mm512_mul_ps(f, _mm512_sub_ps(one, old_a)));
        const __m512 db = _mm512_sub_ps(_mm512_add_ps(_mm512_mul_ps(rb, cb), reaction), _mm512_mul_ps(fk, old_b));
        _mm512_store_ps(next_a + j, _mm512_add_ps(old_a, da));
        _mm512_store_ps(next_b + j, _mm512_add_ps(old_b, db));
    }
    if (j < n)
        update_row<float>(a_up + j, a_mid + j, a_down + j, b_up + j, b_mid + j, b_down + j, next_a + j, next_b + j,
                          n - j, c);
}

#pragma GCC pop_options
#endif

// The row update a kernel runs: update_row_avx512 for float on a CPU (and
// OS) with AVX-512, update_row (its target_clones) otherwise.
template <class Real>
RowUpdate<Real> row_update() {
#ifdef FIGGEN_GS_AVX512
    if constexpr (std::is_same_v<Real, float>)
        if (__builtin_cpu_supports("avx512f")) return update_row_avx512;
#endif
    return update_row<Real>;
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
Grid<Real> GrayScottKernel<Real>::b_as_stored() const {
    return b_[current_].template extract<Real>();
}

template <class Real>
bool GrayScottKernel<Real>::unchanged() const {
    // The other pair holds the state one step back once a step has run.
    const int before = current_ ^ 1;
    return steps_ > 0 && a_[current_].same_bits(a_[before]) && b_[current_].same_bits(b_[before]);
}

template <class Real>
void GrayScottKernel<Real>::step(int steps, int threads) {
    const int n = params_.n;
    const Rates<Real> rates{static_cast<Real>(params_.ra), static_cast<Real>(params_.rb), static_cast<Real>(params_.f),
                            static_cast<Real>(params_.f + params_.k)};
    const int first = current_;
    const RowUpdate<Real> update = row_update<Real>();
    parallel_steps(n, steps, threads, [&](int s, int begin, int end) {
        // float flushes subnormals (see SubnormalsFlushed); double keeps
        // gradual underflow, so that it stays equal to sim::GrayScott.
        std::optional<SubnormalsFlushed> flushed;
        if constexpr (std::is_same_v<Real, float>) flushed.emplace();
        const int from = (first + s) & 1, to = from ^ 1;
        const PaddedRows<Real> a = a_[from].rows(), b = b_[from].rows(), next_a = a_[to].rows(), next_b = b_[to].rows();
        for (int i = begin; i < end; ++i) {
            update(a.row(i - 1), a.row(i), a.row(i + 1), b.row(i - 1), b.row(i), b.row(i + 1), next_a.row(i),
                   next_b.row(i), n, rates);
            next_a.wrap_row(i);
            next_b.wrap_row(i);
        }
    });
    current_ = (first + steps) & 1;
    steps_ += steps;
}

const char* float_kernel_vectors() {
    return row_update<float>() == update_row<float> ? "target_clones" : "avx512f";
}

template class GrayScottKernel<float>;
template class GrayScottKernel<double>;

}  // namespace sim
