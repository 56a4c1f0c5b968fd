#pragma once
// A chain of a compiled formula (sim/formula/program.hpp's Chain) run in
// one pass over a chunk: for each block of cells the value so far stays in
// vector registers from the chain's first operation to its last, instead
// of going to memory between operations. Each operation rounds as it does
// alone, in the same order, so that the result is the same bits as the
// operations one by one (and as Ready's OpenCL).
//
// The vector code is written once (sim/formula/chain_kernels_body.inc) and built
// for AVX-512, for AVX2 with FMA and for plain C++; the widest the
// processor runs is taken at run time. All give the same bits.


#include <cstdint>
#include <memory>
#include <vector>

#include "sim/formula/chain_jit.hpp"
#include "sim/formula/program.hpp"

namespace sim::formula::fused {

// A chain as a straight list of small operations on three vector
// registers (acc, the value so far; aux, a short chain that is an operand;
// g, a stencil's weighted group), each taking at most one row or constant:
// `acc_sub_row` is acc = acc - row, `acc_rsub_k` is acc = k - acc. The run
// goes from one to the next by a jump through a table (threaded code), so
// that a block of cells pays little for each.
enum class Kind : std::uint8_t {
    acc_set_row, acc_set_k, acc_add_row, acc_add_k, acc_sub_row, acc_sub_k, acc_rsub_row, acc_rsub_k,
    acc_mul_row, acc_mul_k, acc_div_k,
    aux_set_row, aux_set_k, aux_add_row, aux_add_k, aux_sub_row, aux_sub_k, aux_rsub_row, aux_rsub_k,
    aux_mul_row, aux_mul_k, aux_div_k,
    g_set_row, g_add_row,   // g = row; g = g + row
    acc_set_wg, acc_add_wg, // acc = k * g; acc = acc + k * g
    acc_fma_wg,             // acc = k * g + acc, rounded once (a stencil in Ready's OpenCL arithmetic)
    // Fused multiply-adds (Op::fma in a chain), each rounded once; the
    // negations before them are exact.
    acc_neg, aux_neg,                     // acc = -acc; aux = -aux
    acc_fma_aux_row, acc_fma_aux_k,       // acc = aux * row + acc; aux * k + acc
    acc_fma_acc_aux_row, acc_fms_acc_aux_row,  // acc = acc * aux + row; acc * aux - row
    acc_fma_acc_aux_k,                    // acc = acc * aux + k
    acc_fma_acc_row_aux, acc_fma_acc_k_aux,    // acc = acc * row + aux; acc * k + aux
    aa_add, aa_sub, aa_rsub, aa_mul,  // acc = acc op aux; rsub: aux - acc
    end,                    // store acc (and check it)
};
constexpr int kinds = static_cast<int>(Kind::end) + 1;

template <class Real>
struct Micro {
    Kind kind = Kind::end;
    int reg = -1;  // the row's register (the *_row kinds)
    Real k = 0;    // the constant (the *_k and *_wg kinds)
};

template <class Real>
struct Plan {
    std::vector<Micro<Real>> code;  // ends with Kind::end
    // The same operations as machine code (sim/formula/chain_jit.hpp),
    // where this processor and build make it; run() takes it while
    // jit_in_use(), else the vector code of isa().
    std::shared_ptr<const ChainCode> machine;
};

// The bytes of machine code the program's chains are given (code_bytes,
// sim/formula/chain_jit.hpp), for memory estimates; 0 where none is made.
double machine_code_bytes(const Program& program);

// The chain for the number type, with its machine code.
Plan<float> plan_float(const Program& program, const Chain& chain);
Plan<double> plan_double(const Program& program, const Chain& chain);

// Runs the chain on lanes 0 .. n - 1 of the registers `view` into d (which
// may be one of the registers it reads: each lane is read before it is
// written). With `check`, returns whether any lane's value is not finite.
bool run(const Plan<float>& plan, const float* const* view, float* d, int n, bool check);
bool run(const Plan<double>& plan, const double* const* view, double* d, int n, bool check);

// The vector code in use, and a way to choose another (the tests compare
// them, and the machine code, sim/formula/chain_jit.hpp, with them).
enum class Isa { plain, avx2, avx512 };
Isa isa();
Isa best_isa();
void use_isa(Isa isa);  // at most best_isa()

}  // namespace sim::formula::fused
