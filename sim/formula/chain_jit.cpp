// A chain's Plan as machine code (sim/formula/chain_jit.hpp), with Xbyak.
//
// The code of a plan, for U vectors of W lanes (U = 4, then U = 1 for the
// last whole vectors), keeps what chain_kernels_body.inc keeps in its
// vector variables in ymm registers:
//   acc: ymm0..3, aux: ymm4..7, g: ymm8..11,
//   ymm12: the operation's constant, broadcast; ymm13: a row loaded;
//   ymm14: the lanes found not finite; ymm15: the sign bit (-0.0).
// and in general registers:
//   rdi: view (the rows, by register), rsi: d, rax: the first lane of the
//   block, rcx: n, r8: check, r9: &bad, r10: the constants, r11: a row.
// Each operation is the instruction the vector code's expression compiles
// to, its operands in an order that gives the same bits (a product is the
// same bits either way round; a fused multiply-add is taken in the form
// whose operands are the expression's, the negations before it exact).
#include "sim/formula/chain_jit.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sim/formula/chain_kernels.hpp"

#if defined(__x86_64__) && defined(FIGGEN_HAVE_XBYAK)
#include <xbyak/xbyak.h>
#define FIGGEN_CHAIN_JIT 1
#endif

namespace sim::formula::fused {

#if defined(FIGGEN_CHAIN_JIT)

namespace {

using Xbyak::Ymm;
using namespace Xbyak::util;

using Entry = int (*)(const void* const* view, void* d, int from, int n, int check, int* bad);

template <class Real>
class Code final : public ChainCode, private Xbyak::CodeGenerator {
public:
    explicit Code(const Plan<Real>& plan)
        : Xbyak::CodeGenerator(code_bytes(plan.code.size()), Xbyak::DontSetProtectRWE) {
        constants_.push_back(Real(-0.0));  // the sign bit
        for (const Micro<Real>& m : plan.code) {
            slot_.push_back(static_cast<int>(constants_.size()));
            constants_.push_back(m.k);
        }
        emit(plan);
        setProtectModeRE();
        entry_ = getCode<Entry>();
    }

    int run(const void* const* view, void* d, int from, int n, bool check, bool& bad) const override {
        int flags = 0;
        const int done = entry_(view, d, from, n, check ? 1 : 0, &flags);
        bad = check && flags != 0;
        return done;
    }

private:
    static constexpr bool dbl = sizeof(Real) == 8;
    static constexpr int W = 32 / static_cast<int>(sizeof(Real));  // lanes in a ymm register
    static constexpr int scale = static_cast<int>(sizeof(Real));

    std::vector<Real> constants_;
    std::vector<int> slot_;  // per operation: its constant's index in constants_
    Entry entry_ = nullptr;

    static Ymm acc(int u) { return Ymm(u); }
    static Ymm aux(int u) { return Ymm(4 + u); }
    static Ymm g(int u) { return Ymm(8 + u); }
    static Ymm k() { return Ymm(12); }
    static Ymm row() { return Ymm(13); }
    static Ymm bad() { return Ymm(14); }
    static Ymm sign() { return Ymm(15); }

    // Lane block u of the row in r11.
    Xbyak::Address at(int u) { return ptr[r11 + rax * scale + u * 32]; }

    void load_row(int reg) { mov(r11, ptr[rdi + static_cast<std::uint32_t>(reg) * 8]); }
    void load_k(int index) {
        if (dbl) vbroadcastsd(k(), ptr[r10 + index * scale]);
        else vbroadcastss(k(), ptr[r10 + index * scale]);
    }

    // The instructions, float or double.
    void op_add(const Ymm& d, const Ymm& a, const Xbyak::Operand& b) { dbl ? vaddpd(d, a, b) : vaddps(d, a, b); }
    void op_sub(const Ymm& d, const Ymm& a, const Xbyak::Operand& b) { dbl ? vsubpd(d, a, b) : vsubps(d, a, b); }
    void op_mul(const Ymm& d, const Ymm& a, const Xbyak::Operand& b) { dbl ? vmulpd(d, a, b) : vmulps(d, a, b); }
    void op_div(const Ymm& d, const Ymm& a, const Xbyak::Operand& b) { dbl ? vdivpd(d, a, b) : vdivps(d, a, b); }
    void move(const Ymm& d, const Xbyak::Operand& a) { dbl ? vmovupd(d, a) : vmovups(d, a); }
    void flip(const Ymm& d, const Ymm& a) { dbl ? vxorpd(d, a, sign()) : vxorps(d, a, sign()); }
    // d = d * b + c; d = b * c + d; d = d * c + b: rounded once.
    void fma213(const Ymm& d, const Ymm& b, const Xbyak::Operand& c) {
        dbl ? vfmadd213pd(d, b, c) : vfmadd213ps(d, b, c);
    }
    void fma231(const Ymm& d, const Ymm& b, const Xbyak::Operand& c) {
        dbl ? vfmadd231pd(d, b, c) : vfmadd231ps(d, b, c);
    }
    void fma132(const Ymm& d, const Ymm& b, const Xbyak::Operand& c) {
        dbl ? vfmadd132pd(d, b, c) : vfmadd132ps(d, b, c);
    }

    // One operation on U vectors.
    void operation(const Micro<Real>& m, int index, int U) {
        const bool reads_row = m.reg >= 0;
        if (reads_row) load_row(m.reg);
        switch (m.kind) {
        case Kind::acc_set_k: case Kind::acc_add_k: case Kind::acc_sub_k: case Kind::acc_rsub_k:
        case Kind::acc_mul_k: case Kind::acc_div_k: case Kind::aux_set_k: case Kind::aux_add_k:
        case Kind::aux_sub_k: case Kind::aux_rsub_k: case Kind::aux_mul_k: case Kind::aux_div_k:
        case Kind::acc_set_wg: case Kind::acc_add_wg: case Kind::acc_fma_wg: case Kind::acc_fma_aux_k:
        case Kind::acc_fma_acc_aux_k: case Kind::acc_fma_acc_k_aux:
            load_k(slot_[static_cast<std::size_t>(index)]);
            break;
        default: break;
        }
        // The kinds on aux are those on acc, from aux_set_row on (chain_kernels.hpp).
        const int first_aux = static_cast<int>(Kind::aux_set_row), kind = static_cast<int>(m.kind);
        const bool on_aux = kind >= first_aux && kind <= static_cast<int>(Kind::aux_div_k);
        const Kind base = on_aux ? static_cast<Kind>(kind - first_aux + static_cast<int>(Kind::acc_set_row)) : m.kind;
        for (int u = 0; u < U; ++u) {
            const Ymm a = acc(u), x = aux(u), gu = g(u);
            const Ymm t = on_aux ? x : a;  // the register an acc or aux kind works on
            switch (base) {
            case Kind::acc_set_row: move(t, at(u)); break;
            case Kind::acc_set_k: move(t, k()); break;
            case Kind::acc_add_row: op_add(t, t, at(u)); break;
            case Kind::acc_add_k: op_add(t, t, k()); break;
            case Kind::acc_sub_row: op_sub(t, t, at(u)); break;
            case Kind::acc_sub_k: op_sub(t, t, k()); break;
            case Kind::acc_rsub_row: move(row(), at(u)); op_sub(t, row(), t); break;
            case Kind::acc_rsub_k: op_sub(t, k(), t); break;
            case Kind::acc_mul_row: op_mul(t, t, at(u)); break;
            case Kind::acc_mul_k: op_mul(t, t, k()); break;
            case Kind::acc_div_k: op_div(t, t, k()); break;
            case Kind::aux_set_row: case Kind::aux_set_k: case Kind::aux_add_row: case Kind::aux_add_k:
            case Kind::aux_sub_row: case Kind::aux_sub_k: case Kind::aux_rsub_row: case Kind::aux_rsub_k:
            case Kind::aux_mul_row: case Kind::aux_mul_k: case Kind::aux_div_k:
                break;  // never here: `base` is their acc kind
            case Kind::g_set_row: move(gu, at(u)); break;
            case Kind::g_add_row: op_add(gu, gu, at(u)); break;
            case Kind::acc_set_wg: op_mul(a, k(), gu); break;                       // k * g
            case Kind::acc_add_wg: op_mul(row(), k(), gu); op_add(a, a, row()); break;  // acc + k * g, rounded twice
            case Kind::acc_fma_wg: fma231(a, k(), gu); break;                    // k * g + acc
            case Kind::acc_neg: flip(a, a); break;
            case Kind::aux_neg: flip(x, x); break;
            case Kind::acc_fma_aux_row: fma231(a, x, at(u)); break;  // aux * row + acc
            case Kind::acc_fma_aux_k: fma231(a, x, k()); break;      // aux * k + acc
            case Kind::acc_fma_acc_aux_row: fma213(a, x, at(u)); break;  // acc * aux + row
            case Kind::acc_fms_acc_aux_row:                                // acc * aux + (-row)
                move(row(), at(u));
                flip(row(), row());
                fma213(a, x, row());
                break;
            case Kind::acc_fma_acc_aux_k: fma213(a, x, k()); break;    // acc * aux + k
            case Kind::acc_fma_acc_row_aux: fma132(a, x, at(u)); break;  // acc * row + aux
            case Kind::acc_fma_acc_k_aux: fma132(a, x, k()); break;      // acc * k + aux
            case Kind::aa_add: op_add(a, a, x); break;
            case Kind::aa_sub: op_sub(a, a, x); break;
            case Kind::aa_rsub: op_sub(a, x, a); break;
            case Kind::aa_mul: op_mul(a, a, x); break;
            case Kind::end: break;
            }
        }
    }

    // The block loop for U vectors: while a whole block fits, the plan's
    // operations, then acc stored (and checked).
    void block_loop(const Plan<Real>& plan, int U) {
        Xbyak::Label top, out, unchecked;
        // acc, aux and g start at zero, as the vector code's.
        for (int r = 0; r < 12; ++r) vxorps(Ymm(r), Ymm(r), Ymm(r));
        // rax + U * W <= n: a whole block left.
        L(top);
        lea(r11, ptr[rax + U * W]);
        cmp(r11, rcx);
        jg(out, T_NEAR);
        for (std::size_t i = 0; i < plan.code.size(); ++i) operation(plan.code[i], static_cast<int>(i), U);
        for (int u = 0; u < U; ++u) move_out(u);
        test(r8d, r8d);
        jz(unchecked, T_NEAR);
        for (int u = 0; u < U; ++u) {
            // acc - acc is NaN where acc is not finite (and else 0).
            op_sub(row(), acc(u), acc(u));
            dbl ? vcmppd(row(), row(), row(), 3) : vcmpps(row(), row(), row(), 3);  // unordered: NaN
            dbl ? vorpd(bad(), bad(), row()) : vorps(bad(), bad(), row());
        }
        L(unchecked);
        Xbyak::CodeGenerator::add(rax, U * W);
        jmp(top, T_NEAR);
        L(out);
    }
    void move_out(int u) {
        dbl ? vmovupd(ptr[rsi + rax * scale + u * 32], acc(u)) : vmovups(ptr[rsi + rax * scale + u * 32], acc(u));
    }

    void emit(const Plan<Real>& plan) {
        // int entry(view, d, from, n, check, bad)
        movsxd(rax, edx);
        movsxd(rcx, ecx);
        mov(r10, reinterpret_cast<std::uintptr_t>(constants_.data()));
        load_k(0);
        move(sign(), k());
        vxorps(bad(), bad(), bad());
        for (int U : {4, 1}) block_loop(plan, U);
        dbl ? vmovmskpd(r11d, bad()) : vmovmskps(r11d, bad());
        mov(ptr[r9], r11d);
        vzeroupper();
        ret();
    }
};

}  // namespace

#endif

namespace {
std::atomic<bool>& enabled() {
    static std::atomic<bool> on{jit_available()};
    return on;
}
}  // namespace

bool jit_available() {
#if defined(FIGGEN_CHAIN_JIT)
    return best_isa() >= Isa::avx2;  // AVX2 with FMA, as the vector code finds them
#else
    return false;
#endif
}

bool jit_in_use() {
    return enabled().load(std::memory_order_relaxed);
}

void use_jit(bool on) {
    enabled().store(on && jit_available());
}

template <class Real>
static std::shared_ptr<const ChainCode> compile_any(const Plan<Real>& plan) {
#if defined(FIGGEN_CHAIN_JIT)
    if (!jit_available()) return nullptr;
    try {
        return std::make_shared<const Code<Real>>(plan);
    } catch (const Xbyak::Error&) {
        return nullptr;  // the vector code runs it
    }
#else
    (void)plan;
    return nullptr;
#endif
}

std::shared_ptr<const ChainCode> compile_chain(const Plan<float>& plan) {
    return compile_any(plan);
}
std::shared_ptr<const ChainCode> compile_chain(const Plan<double>& plan) {
    return compile_any(plan);
}

}  // namespace sim::formula::fused
