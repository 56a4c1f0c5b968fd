#include "sim/gray_scott_kernels.hpp"

#include <cstddef>
#include <optional>
#include <type_traits>

#include "sim/check.hpp"
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

// The rows [begin, end) of one step, each followed by its halo copies (its
// thread's rows: no other thread writes them or reads them before the barrier).
template <class Real>
using RowsUpdate = void (*)(const PaddedRows<Real>& a, const PaddedRows<Real>& b, const PaddedRows<Real>& next_a,
                            const PaddedRows<Real>& next_b, int begin, int end, Rates<Real> c);

// One call of update_row at row i.
template <class Real>
void update_row_at(const PaddedRows<Real>& a, const PaddedRows<Real>& b, const PaddedRows<Real>& next_a,
                   const PaddedRows<Real>& next_b, int i, Rates<Real> c) {
    update_row<Real>(a.row(i - 1), a.row(i), a.row(i + 1), b.row(i - 1), b.row(i), b.row(i + 1), next_a.row(i),
                     next_b.row(i), a.n, c);
}

template <class Real>
void update_rows(const PaddedRows<Real>& a, const PaddedRows<Real>& b, const PaddedRows<Real>& next_a,
                 const PaddedRows<Real>& next_b, int begin, int end, Rates<Real> c) {
    for (int i = begin; i < end; ++i) {
        update_row_at(a, b, next_a, next_b, i, c);
        next_a.wrap_row(i);
        next_b.wrap_row(i);
    }
}

#ifdef FIGGEN_GS_AVX512
#pragma GCC push_options
#pragma GCC target("avx512f")

// The AVX-512 operations the rows below need, for float (16 lanes) and
// double (8 lanes): the same code runs both.
template <class Real>
struct Avx512;

template <>
struct Avx512<float> {
    using V = __m512;
    static constexpr int lanes = 16;
    static V load(const float* p) { return _mm512_load_ps(p); }
    static V loadu(const float* p) { return _mm512_loadu_ps(p); }
    static void store(float* p, V v) { _mm512_store_ps(p, v); }
    static V set1(float x) { return _mm512_set1_ps(x); }
    static V add(V a, V b) { return _mm512_add_ps(a, b); }
    static V sub(V a, V b) { return _mm512_sub_ps(a, b); }
    static V mul(V a, V b) { return _mm512_mul_ps(a, b); }
    // Lanes: before's last, then here's first 15 (valignd). The masked form
    // with every lane set is the same instruction; the plain one trips GCC
    // 12's -Wmaybe-uninitialized in its own header.
    static V shifted(V here, V before) {
        const __m512i bits = _mm512_castps_si512(here);
        return _mm512_castsi512_ps(
            _mm512_mask_alignr_epi32(bits, __mmask16(0xFFFF), bits, _mm512_castps_si512(before), 15));
    }
};

template <>
struct Avx512<double> {
    using V = __m512d;
    static constexpr int lanes = 8;
    static V load(const double* p) { return _mm512_load_pd(p); }
    static V loadu(const double* p) { return _mm512_loadu_pd(p); }
    static void store(double* p, V v) { _mm512_store_pd(p, v); }
    static V set1(double x) { return _mm512_set1_pd(x); }
    static V add(V a, V b) { return _mm512_add_pd(a, b); }
    static V sub(V a, V b) { return _mm512_sub_pd(a, b); }
    static V mul(V a, V b) { return _mm512_mul_pd(a, b); }
    static V shifted(V here, V before) {  // valignq
        const __m512i bits = _mm512_castpd_si512(here);
        return _mm512_castsi512_pd(
            _mm512_mask_alignr_epi64(bits, __mmask8(0xFF), bits, _mm512_castpd_si512(before), 7));
    }
};

// Columns j - 1, j and j + 1 of a row, a vector of cells each.
template <class Real>
struct Columns {
    typename Avx512<Real>::V left, here, right;
};

// One row read block by block (j = 0, 16, 32, ... for float, 0, 8, ... for
// double; column j is 64-byte aligned). Why not three unaligned loads, as
// update_row's AVX-512 clone does: an unaligned 64-byte load always spans
// two cache lines, costing two of the core's loads; the clone's 12 such
// loads a block, not its 33 flops, bound it (float, rows in L1: 3.1 G
// cells/s, 5.7 G/s if every load were aligned). Here the left columns are
// the block before, kept in a register, shifted one lane; only the right
// ones load unaligned.
template <class Real>
struct RowStream {
    using A = Avx512<Real>;
    const Real* row;
    typename A::V before;  // the lanes columns before j

    explicit RowStream(const Real* r) : row(r), before(A::load(r - A::lanes)) {}
    Columns<Real> at(std::ptrdiff_t j) {
        const typename A::V here = A::load(row + j);
        const typename A::V left = A::shifted(here, before);
        before = here;
        return {left, here, A::loadu(row + j + 1)};
    }
};

// update_row's laplacian, the same operations in the same order.
template <class Real>
typename Avx512<Real>::V laplacian(const Columns<Real>& up, const Columns<Real>& mid, const Columns<Real>& down) {
    using A = Avx512<Real>;
    const auto corners = A::add(A::add(up.left, down.right), A::add(up.right, down.left));
    const auto edges = A::add(A::add(up.here, down.here), A::add(mid.left, mid.right));
    const auto weighted =
        A::add(A::mul(A::set1(static_cast<Real>(0.05)), corners), A::mul(A::set1(static_cast<Real>(0.2)), edges));
    return A::sub(weighted, mid.here);
}

template <class Real>
struct BlockRates {
    using A = Avx512<Real>;
    typename A::V ra, rb, f, fk;
    explicit BlockRates(Rates<Real> c) : ra(A::set1(c.ra)), rb(A::set1(c.rb)), f(A::set1(c.f)), fk(A::set1(c.fk)) {}
};

// A vector of cells of a row from the columns of A and B above, at and below
// them: update_row's arithmetic, lane by lane, in its order (no FMA), so the
// same bits.
template <class Real>
inline void update_block(const Columns<Real>& au, const Columns<Real>& am, const Columns<Real>& ad,
                         const Columns<Real>& bu, const Columns<Real>& bm, const Columns<Real>& bd,
                         const BlockRates<Real>& c, Real* next_a, Real* next_b) {
    using A = Avx512<Real>;
    const auto ca = laplacian(au, am, ad), cb = laplacian(bu, bm, bd), old_a = am.here, old_b = bm.here;
    const auto reaction = A::mul(old_a, A::mul(old_b, old_b));
    const auto da = A::add(A::sub(A::mul(c.ra, ca), reaction), A::mul(c.f, A::sub(A::set1(Real(1)), old_a)));
    const auto db = A::sub(A::add(A::mul(c.rb, cb), reaction), A::mul(c.fk, old_b));
    A::store(next_a, A::add(old_a, da));
    A::store(next_b, A::add(old_b, db));
}

// Rows i and i + 1 at once, block by block: they share the input rows i and
// i + 1, so a block reads and shifts 4 rows of each field for its 2 outputs
// instead of 6 (float, rows in L1: 7-14% faster than one row at a time).
// update_row itself does the last n % lanes cells of each.
template <class Real>
void update_row_pair_avx512(const PaddedRows<Real>& a, const PaddedRows<Real>& b, const PaddedRows<Real>& next_a,
                            const PaddedRows<Real>& next_b, int i, Rates<Real> c) {
    constexpr int lanes = Avx512<Real>::lanes;
    RowStream<Real> a0(a.row(i - 1)), a1(a.row(i)), a2(a.row(i + 1)), a3(a.row(i + 2));
    RowStream<Real> b0(b.row(i - 1)), b1(b.row(i)), b2(b.row(i + 1)), b3(b.row(i + 2));
    Real *na0 = next_a.row(i), *na1 = next_a.row(i + 1), *nb0 = next_b.row(i), *nb1 = next_b.row(i + 1);
    const BlockRates<Real> rates(c);
    const std::ptrdiff_t n = a.n;
    std::ptrdiff_t j = 0;
    for (; j + lanes <= n; j += lanes) {
        const Columns<Real> au = a0.at(j), am = a1.at(j), ad = a2.at(j), aw = a3.at(j);
        const Columns<Real> bu = b0.at(j), bm = b1.at(j), bd = b2.at(j), bw = b3.at(j);
        update_block(au, am, ad, bu, bm, bd, rates, na0 + j, nb0 + j);
        update_block(am, ad, aw, bm, bd, bw, rates, na1 + j, nb1 + j);
    }
    for (int k = i; j < n && k <= i + 1; ++k)
        update_row<Real>(a.row(k - 1) + j, a.row(k) + j, a.row(k + 1) + j, b.row(k - 1) + j, b.row(k) + j,
                         b.row(k + 1) + j, next_a.row(k) + j, next_b.row(k) + j, n - j, c);
}

// update_rows with AVX-512: pairs of rows, an odd last row by update_row.
template <class Real>
void update_rows_avx512(const PaddedRows<Real>& a, const PaddedRows<Real>& b, const PaddedRows<Real>& next_a,
                        const PaddedRows<Real>& next_b, int begin, int end, Rates<Real> c) {
    int i = begin;
    for (; i + 1 < end; i += 2) {
        update_row_pair_avx512(a, b, next_a, next_b, i, c);
        for (int k : {i, i + 1}) {
            next_a.wrap_row(k);
            next_b.wrap_row(k);
        }
    }
    if (i < end) update_rows(a, b, next_a, next_b, i, end, c);
}

#pragma GCC pop_options
#endif

// The rows update a kernel runs: update_rows_avx512 on a CPU (and OS) with
// AVX-512, update_rows (update_row's target_clones) otherwise.
template <class Real>
RowsUpdate<Real> rows_update() {
#ifdef FIGGEN_GS_AVX512
    if (__builtin_cpu_supports("avx512f")) return update_rows_avx512<Real>;
#endif
    return update_rows<Real>;
}

}  // namespace

template <class Real>
GrayScottKernel<Real>::GrayScottKernel(const GrayScottParams& params, const Grid<double>& a, const Grid<double>& b) {
    restart(params, a, b);
}

template <class Real>
void GrayScottKernel<Real>::restart(const GrayScottParams& params, const Grid<double>& a, const Grid<double>& b) {
    params.validate();
    require_square_field("A", a, params.n);
    require_square_field("B", b, params.n);
    if (a_[0].n() != params.n)
        for (PaddedField<Real>* field : {&a_[0], &a_[1], &b_[0], &b_[1]}) *field = PaddedField<Real>(params.n);
    params_ = params;
    a_[0].load(a);
    b_[0].load(b);
    current_ = 0;
    steps_ = 0;
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
    const Rates<Real> rates{static_cast<Real>(params_.ra), static_cast<Real>(params_.rb), static_cast<Real>(params_.f),
                            static_cast<Real>(params_.f + params_.k)};
    const int first = current_;
    const RowsUpdate<Real> update = rows_update<Real>();
    parallel_steps(params_.n, steps, threads, [&](int s, int begin, int end) {
        // float flushes subnormals (see SubnormalsFlushed); double keeps
        // gradual underflow, so that it stays equal to sim::GrayScott.
        std::optional<SubnormalsFlushed> flushed;
        if constexpr (std::is_same_v<Real, float>) flushed.emplace();
        const int from = (first + s) & 1, to = from ^ 1;
        const PaddedRows<Real> a = a_[from].rows(), b = b_[from].rows(), next_a = a_[to].rows(), next_b = b_[to].rows();
        update(a, b, next_a, next_b, begin, end, rates);
    });
    current_ = (first + steps) & 1;
    steps_ += steps;
}

const char* float_kernel_vectors() {
    return rows_update<float>() == update_rows<float> ? "target_clones" : "avx512f";
}

template class GrayScottKernel<float>;
template class GrayScottKernel<double>;

}  // namespace sim
