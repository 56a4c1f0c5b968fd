#pragma once
// The operations of a compiled kernel (sim/kernel/lanes.hpp), chosen by
// the compiler for each type; sim/kernel/exec.cpp defines them.

#include "sim/kernel/lanes.hpp"

namespace sim::kernel::ops {

enum class Unary { neg, bit_not, log_not, vec_not };
enum class Binary { add, sub, mul, div, rem, bit_and, bit_or, bit_xor, shl, shr };
enum class Compare { eq, ne, lt, gt, le, ge };
enum class Math1 {
    sqrt, rsqrt, cbrt, exp, exp2, exp10, expm1, log, log2, log10, log1p, sin, cos, tan, asin, acos, atan, sinh, cosh,
    tanh, asinh, acosh, atanh, fabs, floor, ceil, round, trunc, rint, sign, erf, erfc, tgamma, lgamma,
    iabs,  // abs of an integer (into its unsigned type's bits)
    isnan, isinf, isfinite,  // into int: 0/1 (scalar) or -1/0 (vector: vec true)
};
enum class Math2 {
    pow, atan2, hypot, fmod, fmin, fmax, min, max, step, copysign, fdim, remainder, powr,
    isless, isgreater, islessequal, isgreaterequal, isequal, isnotequal,
};
enum class Math3 { clamp, mix, fma, mad, smoothstep };

OpFn constant(Scalar s);                      // dst = i (integers) or f (floats), uniform
OpFn convert(Scalar from, Scalar to);         // dst = (to) a
OpFn convert_sat(Scalar from, Scalar to);     // dst = convert_to_sat_rtz(a): from a float to an integer
OpFn copy(Scalar s);                          // dst = a, every lane
OpFn assign(Scalar s);                        // dst = a in the mask's lanes
OpFn unary(Unary u, Scalar s, Scalar result); // log_not, vec_not: into `result`
OpFn binary(Binary b, Scalar s);
OpFn compare(Compare c, Scalar s, Scalar result, bool vector);  // 0/1, or -1/0 for a vector
OpFn math1(Math1 m, Scalar s, bool vector = false);
OpFn math2(Math2 m, Scalar s, bool vector = false);
OpFn math3(Math3 m, Scalar s);
OpFn select(Scalar s);                        // dst = mask c ? b : a

OpFn to_mask(Scalar s);                       // mask dst = a != 0
OpFn sign_mask(Scalar s);                     // mask dst = a's top bit (select's vector rule)
OpFn from_mask();                             // i32 dst = mask a (0/1)
OpFn mask_and();                              // mask dst = mask a & mask b
OpFn mask_or();
OpFn mask_not();                              // mask dst = !mask a (lanes of the chunk)

OpFn check_index();                           // a (i64) within [0, i) in the mask, else fail naming array aux
OpFn buffer_load(Scalar s);                   // dst = view aux's element a, component i (c = 1: a, checked by the op before)
OpFn buffer_store(Scalar s);                  // view aux's element a, component i = b, in the mask
OpFn array_load(Scalar s);                    // dst = array aux's element a, component i
OpFn array_store(Scalar s);                   // array aux's element a, component i = b, in the mask
OpFn global_size();                           // dst (u64) = get_global_size(i), uniform

OpFn if_node();                               // ifs[aux]
OpFn loop_node();                             // loops[aux]
OpFn switch_node();                           // switches[aux]
OpFn guard_node();                            // guards[aux]
OpFn jump();                                  // break, continue, return: mask aux |= the mask; the mask: none
OpFn call_node();                             // calls[aux]

}  // namespace sim::kernel::ops
