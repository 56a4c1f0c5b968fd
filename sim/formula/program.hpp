#pragma once
// A formula compiled (sim/formula/lower.cpp, then sim/formula/passes.hpp):
// a straight list of operations, each over a run of cells of one row at a
// time (a chunk), on numbered registers. Loops are unrolled, `if` and `?:` on values of the
// cells become selections, and everything the formula fixes before the run
// (parameters, literals, loop counters, array indices) is folded into
// constants. sim/formula/run.cpp runs it.

#include <cstdint>
#include <string>
#include <vector>

#include "sim/formula/rule.hpp"

namespace sim::formula {

enum class Op : std::uint8_t {
    copy,                         // a
    add, sub, mul, div,           // a op b
    neg,                          // -a
    select,                       // c != 0 ? b : a   (OpenCL's select(a, b, c))
    less, less_equal, equal, not_equal,  // a op b: `truth` or 0
    logical_and, logical_or,      // both / either nonzero: `truth` or 0
    logical_not,                  // a == 0: `truth` or 0 (OpenCL's ! on a float4 gives -1)
    trunc_int,                    // a converted to int (toward zero)
    int_div, int_mod,             // a / b, a % b on ints (toward zero)
    call1, call2, call3,          // fn(a), fn(a, b), fn(a, b, c)
    stencil,                      // Program::stencils[a]: a weighted sum of inputs, in one pass
    chain,                        // Program::chains[a]: several operations in one pass (below)
    fma,                          // (+/-)a * b (+/-) c rounded once (Instr::signs): Ready's OpenCL contracts
};

// The built-in functions (an allow-list, sim/formula/lower.cpp).
enum class Fn : std::uint8_t {
    sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, asinh, acosh, atanh,
    exp, exp2, exp10, expm1, log, log2, log10, log1p, sqrt, rsqrt, cbrt,
    fabs, floor, ceil, round, trunc, rint, sign, degrees, radians, abs_int,
    pow, atan2, fmin, fmax, fmod, hypot, step, copysign, fdim,
    clamp, mix, smoothstep, mad,
};

struct Instr {
    Op op = Op::copy;
    Fn fn = Fn::sin;
    double truth = 1;  // the value of true for comparisons: 1, or -1 for Ready's float4
    int dst = 0, a = -1, b = -1, c = -1;
    int mask = -1;  // for div: checked for zero divisors only where this register is nonzero (-1: everywhere)
    std::uint8_t signs = 0;  // for fma: negate_product and/or negate_addend
    Pos pos;        // in the formula, for errors
    static constexpr std::uint8_t negate_product = 1, negate_addend = 2;
};

// A stencil in one operation, Ready's order of operations kept: the terms
// added left to right, each an input (weight 1) or weight * (the sum of its
// inputs, left to right); then, if `divide`, divided by `divisor`. With
// `fused` (Ready's OpenCL arithmetic), a weighted term and the addition it
// meets round once, as clang contracts them: the first term's product with
// the second term, and every later one's with the sum so far.
struct StencilSum {
    struct Term {
        double weight = 1;        // 1: a single input, added as it is
        std::vector<int> inputs;  // registers
    };
    std::vector<Term> terms;
    bool divide = false;
    double divisor = 1;  // rounded to the number type
    bool fused = false;
};

// Operations fused into one pass over the chunk (sim/formula/chain_kernels.hpp),
// each value rounded as the operation alone rounds it: a stencil or a
// binary operation, then operations that each take the value so far and
// one operand. An operand may itself be a short chain, kept in a second
// accumulator (`aux`). Only add, sub, mul, and div by a nonzero constant
// go into a chain: nothing in one can fail.
struct Chain {
    enum class Kind : std::uint8_t {
        stencil,  // acc = Program::stencils[stencil]
        binary,   // acc = x op y
        acc,      // acc = acc op x (t_first), or x op acc
        aux,      // aux = x op y
        aux_op,   // aux = aux op x (t_first), or x op aux
        acc_aux,  // acc = acc op aux (t_first), or aux op acc
        // An fma (Op::fma, its signs) with the value so far as its operand
        // `slot` (0 a, 1 b: a factor; 2 c: the addend), the aux chain just
        // before as operand `aux_slot` (-1: none), and the rest x, then y,
        // in operand order.
        fma,
    };
    struct Step {
        Kind kind = Kind::binary;
        Op op = Op::add;
        bool t_first = true;
        int x = -1, y = -1;     // registers; -1: the constant kx or ky
        double kx = 0, ky = 0;  // rounded to the number type
        int stencil = -1;
        int slot = 2, aux_slot = -1;  // fma
        std::uint8_t signs = 0;       // fma: Instr::negate_product, negate_addend
    };
    std::vector<Step> steps;
};

struct Program {
    // Registers 0 .. registers - 1 each hold a chunk of values. Some are
    // views into the model's rows (inputs, outputs), some constants
    // (filled once), the rest buffers the operations write.
    int registers = 0;
    struct Constant {
        int reg;
        double value;  // already rounded to the model's number type
    };
    std::vector<Constant> constants;
    // Chemical `chemical` at offset (dx, dy, dz) from each cell.
    struct Input {
        int reg, chemical, dx, dy, dz;
    };
    std::vector<Input> inputs;
    int x_pos = -1, y_pos = -1, z_pos = -1;  // registers of x_pos, y_pos and z_pos, if used
    std::vector<Instr> code;
    std::vector<StencilSum> stencils;
    std::vector<Chain> chains;
    int operations = 0;  // the operations before any were fused into chains
    // Per chemical: the register of its new value, X + timestep * delta_X
    // (Integrator::euler), or of delta_X itself (the other integrators,
    // whose stages the run combines).
    std::vector<int> outputs;
    bool outputs_are_deltas = false;
    int radius_x = 0, radius_y = 0, radius_z = 0;  // the farthest neighbour read
};

// The registers an instruction reads: its operands, a stencil's inputs, a
// chain's operands.
std::vector<int> sources(const Program& program, const Instr& in);

// Compiles `rule` (validated) for a grid of `dimensions` (1, 2 or 3, as
// dimensionality() counts them: its stencils): parsed
// (sim/formula/parse.cpp), lowered (sim/formula/lower.cpp) and passed over
// (sim/formula/passes.hpp). The program is the same for any grid of those
// dimensions. Throws FormulaError.
Program compile(const Rule& rule, int dimensions = 2);

}  // namespace sim::formula
