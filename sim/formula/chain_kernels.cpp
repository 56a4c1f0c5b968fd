// Chains of a compiled formula in one pass (sim/formula/chain_kernels.hpp): the
// vector code of sim/formula/chain_kernels_body.inc for each instruction set, the
// choice among them, and the proof behind each division by multiplication.
#include "sim/formula/chain_kernels.hpp"

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <algorithm>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

// The vector code jumps from operation to operation through a table of
// label addresses (GCC's labels as values, sim/formula/chain_kernels_body.inc).
#pragma GCC diagnostic ignored "-Wpedantic"

namespace sim::formula::fused {

namespace {

// One lane at a time, any processor.
template <class R>
struct Plain {
    using Real = R;
    using V = R;
    using M = bool;
    static constexpr int W = 1;
    static V load(const R* p) { return *p; }
    static void store(R* p, V v) { *p = v; }
    static V set1(R v) { return v; }
    static V fma(V a, V b, V c) { return std::fma(a, b, c); }
    static V neg(V a) { return -a; }
    static M clear() { return false; }
    static M not_finite(V v) { return (v - v) != R(0); }  // inf - inf and NaN - NaN are NaN
    static M either(M a, M b) { return a || b; }
    static bool any(M m) { return m; }
};

namespace plain {
#include "sim/formula/chain_kernels_body.inc"
}  // namespace plain

}  // namespace

// GCC alone: clang (the fuzz build) has no #pragma GCC target, and takes the plain code.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FIGGEN_FUSED_X86 1

#pragma GCC push_options
#pragma GCC target("avx2,fma")
namespace avx2 {
namespace {

struct F {
    using Real = float;
    using V = __m256;
    using M = __m256;
    static constexpr int W = 8;
    static V load(const float* p) { return _mm256_loadu_ps(p); }
    static void store(float* p, V v) { _mm256_storeu_ps(p, v); }
    static V set1(float v) { return _mm256_set1_ps(v); }
    static V fma(V a, V b, V c) { return _mm256_fmadd_ps(a, b, c); }
    static V neg(V a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
    static M clear() { return _mm256_setzero_ps(); }
    static M not_finite(V v) { return _mm256_cmp_ps(_mm256_sub_ps(v, v), _mm256_setzero_ps(), _CMP_NEQ_UQ); }
    static M either(M a, M b) { return _mm256_or_ps(a, b); }
    static bool any(M m) { return _mm256_movemask_ps(m) != 0; }
};

struct D {
    using Real = double;
    using V = __m256d;
    using M = __m256d;
    static constexpr int W = 4;
    static V load(const double* p) { return _mm256_loadu_pd(p); }
    static void store(double* p, V v) { _mm256_storeu_pd(p, v); }
    static V set1(double v) { return _mm256_set1_pd(v); }
    static V fma(V a, V b, V c) { return _mm256_fmadd_pd(a, b, c); }
    static V neg(V a) { return _mm256_xor_pd(a, _mm256_set1_pd(-0.0)); }
    static M clear() { return _mm256_setzero_pd(); }
    static M not_finite(V v) { return _mm256_cmp_pd(_mm256_sub_pd(v, v), _mm256_setzero_pd(), _CMP_NEQ_UQ); }
    static M either(M a, M b) { return _mm256_or_pd(a, b); }
    static bool any(M m) { return _mm256_movemask_pd(m) != 0; }
};

#include "sim/formula/chain_kernels_body.inc"

}  // namespace

int run_f(const Plan<float>& p, const float* const* view, float* d, int n, bool check, bool& bad) {
    return chain_vectors<F, 4>(p, view, d, n, check, bad);
}
int run_d(const Plan<double>& p, const double* const* view, double* d, int n, bool check, bool& bad) {
    return chain_vectors<D, 4>(p, view, d, n, check, bad);
}

}  // namespace avx2
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx512f,avx2,fma")
namespace avx512 {
namespace {

struct F {
    using Real = float;
    using V = __m512;
    using M = __mmask16;
    static constexpr int W = 16;
    static V load(const float* p) { return _mm512_loadu_ps(p); }
    static void store(float* p, V v) { _mm512_storeu_ps(p, v); }
    static V set1(float v) { return _mm512_set1_ps(v); }
    static V fma(V a, V b, V c) { return _mm512_fmadd_ps(a, b, c); }
    static V neg(V a) { return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_set1_epi32(INT32_MIN))); }
    static M clear() { return 0; }
    static M not_finite(V v) { return _mm512_cmp_ps_mask(_mm512_sub_ps(v, v), _mm512_setzero_ps(), _CMP_NEQ_UQ); }
    static M either(M a, M b) { return static_cast<M>(a | b); }
    static bool any(M m) { return m != 0; }
};

struct D {
    using Real = double;
    using V = __m512d;
    using M = __mmask8;
    static constexpr int W = 8;
    static V load(const double* p) { return _mm512_loadu_pd(p); }
    static void store(double* p, V v) { _mm512_storeu_pd(p, v); }
    static V set1(double v) { return _mm512_set1_pd(v); }
    static V fma(V a, V b, V c) { return _mm512_fmadd_pd(a, b, c); }
    static V neg(V a) { return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(INT64_MIN))); }
    static M clear() { return 0; }
    static M not_finite(V v) { return _mm512_cmp_pd_mask(_mm512_sub_pd(v, v), _mm512_setzero_pd(), _CMP_NEQ_UQ); }
    static M either(M a, M b) { return static_cast<M>(a | b); }
    static bool any(M m) { return m != 0; }
};

#include "sim/formula/chain_kernels_body.inc"

}  // namespace

int run_f(const Plan<float>& p, const float* const* view, float* d, int n, bool check, bool& bad) {
    return chain_vectors<F, 4>(p, view, d, n, check, bad);
}
int run_d(const Plan<double>& p, const double* const* view, double* d, int n, bool check, bool& bad) {
    return chain_vectors<D, 4>(p, view, d, n, check, bad);
}

}  // namespace avx512
#pragma GCC pop_options
#endif

namespace {

Isa detect() {
#if defined(FIGGEN_FUSED_X86)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return Isa::avx512;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return Isa::avx2;
#endif
    return Isa::plain;
}

std::atomic<Isa>& current() {
    static std::atomic<Isa> isa{best_isa()};
    return isa;
}

template <class Real>
bool run_any(const Plan<Real>& p, const Real* const* view, Real* d, int n, bool check) {
    bool bad = false;
    int done = 0;
    if (p.machine && jit_in_use()) {
        done = p.machine->run(reinterpret_cast<const void* const*>(view), d, 0, n, check, bad);
    } else {
#if defined(FIGGEN_FUSED_X86)
    switch (current().load(std::memory_order_relaxed)) {
    case Isa::avx512:
        if constexpr (sizeof(Real) == 4) done = avx512::run_f(p, view, d, n, check, bad);
        else done = avx512::run_d(p, view, d, n, check, bad);
        break;
    case Isa::avx2:
        if constexpr (sizeof(Real) == 4) done = avx2::run_f(p, view, d, n, check, bad);
        else done = avx2::run_d(p, view, d, n, check, bad);
        break;
    case Isa::plain: break;
    }
#endif
    }
    if (done < n) {
        // The lanes after the last whole vector, one at a time.
        bool rest = false;
        plain::chain_lanes<Plain<Real>, 1>(p, view, d, done, n, check, rest);
        bad |= rest;
    }
    return bad;
}

// The chain's steps as operations on acc, aux and g (sim/formula/chain_kernels.hpp).
template <class Real>
Plan<Real> make_plan(const Program& program, const Chain& chain) {
    Plan<Real> plan;
    auto add = [&](Kind kind, int reg, double k) { plan.code.push_back({kind, reg, static_cast<Real>(k)}); };
    // The kinds of acc (or aux: the same list from aux_set_row on).
    auto on = [](bool aux, Kind kind) {
        return aux ? static_cast<Kind>(static_cast<int>(kind) - static_cast<int>(Kind::acc_set_row) +
                                       static_cast<int>(Kind::aux_set_row))
                   : kind;
    };
    // t = t op x (t_first) or x op t, x a row or a constant.
    auto with = [&](bool aux, Op op, bool t_first, int reg, double k) {
        const bool row = reg >= 0;
        Kind kind;
        switch (op) {
        case Op::add: kind = row ? Kind::acc_add_row : Kind::acc_add_k; break;
        case Op::mul: kind = row ? Kind::acc_mul_row : Kind::acc_mul_k; break;
        case Op::sub:
            kind = t_first ? (row ? Kind::acc_sub_row : Kind::acc_sub_k) : (row ? Kind::acc_rsub_row : Kind::acc_rsub_k);
            break;
        case Op::div:
            if (row || !t_first || k == 0) throw std::logic_error("a chain divides by a value of the cells");
            kind = Kind::acc_div_k;
            break;
        default: throw std::logic_error("a chain holds an operation it cannot run");
        }
        add(on(aux, kind), reg, k);
    };
    // t = x op y.
    auto binary = [&](bool aux, const Chain::Step& st) {
        add(on(aux, st.x >= 0 ? Kind::acc_set_row : Kind::acc_set_k), st.x, st.kx);
        with(aux, st.op, true, st.y, st.ky);
    };
    for (const Chain::Step& st : chain.steps) {
        switch (st.kind) {
        case Chain::Kind::stencil: {
            // The terms left to right: a single input, or weight * (its
            // inputs left to right); then the division.
            const StencilSum& sum = program.stencils[static_cast<std::size_t>(st.stencil)];
            if (sum.fused) {
                // Ready's OpenCL arithmetic: a weighted term meets the
                // addition after it in one rounding. The first two terms:
                // (k0 * g0) + t1 is fma(k0, g0, t1), t1 rounded alone (and
                // a lone weighted input is its group of one); after that
                // acc + k * g is fma(k, g, acc).
                auto group = [&](const StencilSum::Term& t) {
                    add(Kind::g_set_row, t.inputs[0], 0);
                    for (std::size_t k = 1; k < t.inputs.size(); ++k) add(Kind::g_add_row, t.inputs[k], 0);
                };
                auto weighted = [](const StencilSum::Term& t) { return t.weight != 1 || t.inputs.size() > 1; };
                const auto& terms = sum.terms;
                std::size_t next = 1;
                if (terms.size() >= 2 && weighted(terms[0])) {
                    if (weighted(terms[1])) {
                        group(terms[1]);
                        add(Kind::acc_set_wg, -1, terms[1].weight);
                    } else {
                        add(Kind::acc_set_row, terms[1].inputs[0], 0);
                    }
                    group(terms[0]);
                    add(Kind::acc_fma_wg, -1, terms[0].weight);
                    next = 2;
                } else if (weighted(terms[0])) {
                    group(terms[0]);
                    add(Kind::acc_set_wg, -1, terms[0].weight);
                } else {
                    add(Kind::acc_set_row, terms[0].inputs[0], 0);
                }
                for (std::size_t i = next; i < terms.size(); ++i) {
                    if (weighted(terms[i])) {
                        group(terms[i]);
                        add(Kind::acc_fma_wg, -1, terms[i].weight);
                    } else {
                        add(Kind::acc_add_row, terms[i].inputs[0], 0);
                    }
                }
                if (sum.divide) add(Kind::acc_div_k, -1, sum.divisor);
                break;
            }
            bool first = true;
            for (const StencilSum::Term& t : sum.terms) {
                if (t.inputs.size() == 1 && (t.weight == 1 || first)) {
                    add(first ? Kind::acc_set_row : Kind::acc_add_row, t.inputs[0], 0);
                    if (t.weight != 1) add(Kind::acc_mul_k, -1, t.weight);  // Ready's weighted centre first
                } else {
                    add(Kind::g_set_row, t.inputs[0], 0);
                    for (std::size_t k = 1; k < t.inputs.size(); ++k) add(Kind::g_add_row, t.inputs[k], 0);
                    add(first ? Kind::acc_set_wg : Kind::acc_add_wg, -1, t.weight);
                }
                first = false;
            }
            if (sum.divide) add(Kind::acc_div_k, -1, sum.divisor);
            break;
        }
        case Chain::Kind::fma: {
            // (+/-) p * q (+/-) r with acc as operand `slot`, aux (if any)
            // as `aux_slot`, the rest (x, then y) rows or constants.
            struct Operand {
                bool acc = false, aux = false;
                int reg = -1;
                double k = 0;
            };
            Operand o[3];
            bool first = true;
            for (int s = 0; s < 3; ++s) {
                if (s == st.slot) o[s].acc = true;
                else if (s == st.aux_slot) o[s].aux = true;
                else {
                    o[s].reg = first ? st.x : st.y;
                    o[s].k = first ? st.kx : st.ky;
                    first = false;
                }
            }
            const bool negate_product = st.signs & Instr::negate_product, negate_addend = st.signs & Instr::negate_addend;
            auto load_aux = [&](const Operand& op) { add(op.reg >= 0 ? Kind::aux_set_row : Kind::aux_set_k, op.reg, op.k); };
            if (st.slot == 2) {
                // acc is the addend: aux holds one factor, the other is a row or a constant.
                if (negate_addend) add(Kind::acc_neg, -1, 0);
                const Operand* with_aux = o[0].aux ? &o[1] : o[1].aux ? &o[0] : nullptr;
                if (!with_aux) {
                    load_aux(o[0]);
                    with_aux = &o[1];
                }
                if (negate_product) add(Kind::aux_neg, -1, 0);
                add(with_aux->reg >= 0 ? Kind::acc_fma_aux_row : Kind::acc_fma_aux_k, with_aux->reg, with_aux->k);
            } else {
                // acc is a factor; q the other factor, r the addend.
                if (negate_product) add(Kind::acc_neg, -1, 0);
                const Operand& q = o[st.slot == 0 ? 1 : 0];
                const Operand& r = o[2];
                if (r.aux) {
                    if (negate_addend) add(Kind::aux_neg, -1, 0);
                    add(q.reg >= 0 ? Kind::acc_fma_acc_row_aux : Kind::acc_fma_acc_k_aux, q.reg, q.k);
                } else {
                    if (!q.aux) load_aux(q);
                    if (r.reg >= 0) add(negate_addend ? Kind::acc_fms_acc_aux_row : Kind::acc_fma_acc_aux_row, r.reg, 0);
                    else add(Kind::acc_fma_acc_aux_k, -1, negate_addend ? -r.k : r.k);
                }
            }
            break;
        }
        case Chain::Kind::binary: binary(false, st); break;
        case Chain::Kind::aux: binary(true, st); break;
        case Chain::Kind::acc: with(false, st.op, st.t_first, st.x, st.kx); break;
        case Chain::Kind::aux_op: with(true, st.op, st.t_first, st.x, st.kx); break;
        case Chain::Kind::acc_aux:
            switch (st.op) {
            case Op::add: add(Kind::aa_add, -1, 0); break;
            case Op::mul: add(Kind::aa_mul, -1, 0); break;
            case Op::sub: add(st.t_first ? Kind::aa_sub : Kind::aa_rsub, -1, 0); break;
            default: throw std::logic_error("a chain divides by a value of the cells");
            }
            break;
        }
    }
    add(Kind::end, -1, 0);
    return plan;
}

}  // namespace

Plan<float> plan_float(const Program& program, const Chain& chain) {
    Plan<float> plan = make_plan<float>(program, chain);
    plan.machine = compile_chain(plan);
    return plan;
}
Plan<double> plan_double(const Program& program, const Chain& chain) {
    Plan<double> plan = make_plan<double>(program, chain);
    plan.machine = compile_chain(plan);
    return plan;
}

double machine_code_bytes(const Program& program) {
    if (!jit_available()) return 0;
    double bytes = 0;
    for (const Chain& chain : program.chains)
        bytes += static_cast<double>(code_bytes(make_plan<float>(program, chain).code.size()));
    return bytes;
}

bool run(const Plan<float>& plan, const float* const* view, float* d, int n, bool check) {
    return run_any(plan, view, d, n, check);
}
bool run(const Plan<double>& plan, const double* const* view, double* d, int n, bool check) {
    return run_any(plan, view, d, n, check);
}

Isa best_isa() {
    static const Isa best = detect();
    return best;
}
Isa isa() {
    return current().load();
}
void use_isa(Isa wanted) {
    if (static_cast<int>(wanted) > static_cast<int>(best_isa()))
        throw std::invalid_argument("this processor cannot run that instruction set");
    current().store(wanted);
}

}  // namespace sim::formula::fused
