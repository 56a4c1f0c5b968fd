#pragma once
// One value of a formula's operation or built-in function, in the model's
// number type (float or double): what sim/formula/lower.cpp folds before
// the run and what sim/formula/run.cpp computes for each cell, so that the
// two agree bit for bit. OpenCL's definitions where C's differ (sign, step,
// clamp, mix, smoothstep, rsqrt, degrees, radians).

#include <cmath>

#include "sim/formula/program.hpp"

namespace sim::formula {

template <class Real>
inline Real scalar_op(Op op, Real a, Real b, Real truth) {
    switch (op) {
    case Op::copy: return a;
    case Op::add: return a + b;
    case Op::sub: return a - b;
    case Op::mul: return a * b;
    case Op::div: return a / b;
    case Op::neg: return -a;
    case Op::less: return a < b ? truth : Real(0);
    case Op::less_equal: return a <= b ? truth : Real(0);
    case Op::equal: return a == b ? truth : Real(0);
    case Op::not_equal: return a != b ? truth : Real(0);
    case Op::logical_and: return a != 0 && b != 0 ? truth : Real(0);
    case Op::logical_or: return a != 0 || b != 0 ? truth : Real(0);
    case Op::logical_not: return a == 0 ? truth : Real(0);
    case Op::trunc_int: return std::trunc(a);
    case Op::int_div: return b == 0 ? Real(0) : std::trunc(a / b);
    case Op::int_mod: return b == 0 ? Real(0) : std::fmod(std::trunc(a), std::trunc(b));
    default: return 0;
    }
}

template <class Real>
inline Real scalar_call(Fn fn, Real a, Real b, Real c) {
    constexpr Real pi = Real(3.14159265358979323846);
    switch (fn) {
    case Fn::sin: return std::sin(a);
    case Fn::cos: return std::cos(a);
    case Fn::tan: return std::tan(a);
    case Fn::asin: return std::asin(a);
    case Fn::acos: return std::acos(a);
    case Fn::atan: return std::atan(a);
    case Fn::sinh: return std::sinh(a);
    case Fn::cosh: return std::cosh(a);
    case Fn::tanh: return std::tanh(a);
    case Fn::asinh: return std::asinh(a);
    case Fn::acosh: return std::acosh(a);
    case Fn::atanh: return std::atanh(a);
    case Fn::exp: return std::exp(a);
    case Fn::exp2: return std::exp2(a);
    case Fn::exp10: return std::pow(Real(10), a);
    case Fn::expm1: return std::expm1(a);
    case Fn::log: return std::log(a);
    case Fn::log2: return std::log2(a);
    case Fn::log10: return std::log10(a);
    case Fn::log1p: return std::log1p(a);
    case Fn::sqrt: return std::sqrt(a);
    case Fn::rsqrt: return Real(1) / std::sqrt(a);
    case Fn::cbrt: return std::cbrt(a);
    case Fn::fabs: return std::fabs(a);
    case Fn::floor: return std::floor(a);
    case Fn::ceil: return std::ceil(a);
    case Fn::round: return std::round(a);
    case Fn::trunc: return std::trunc(a);
    case Fn::rint: return std::rint(a);
    case Fn::sign: return a > 0 ? Real(1) : a < 0 ? Real(-1) : std::isnan(a) ? Real(0) : a;  // keeps -0.0
    case Fn::degrees: return a * (Real(180) / pi);
    case Fn::radians: return a * (pi / Real(180));
    case Fn::abs_int: return std::fabs(a);
    case Fn::pow: return std::pow(a, b);
    case Fn::atan2: return std::atan2(a, b);
    case Fn::fmin: return std::fmin(a, b);
    case Fn::fmax: return std::fmax(a, b);
    case Fn::fmod: return std::fmod(a, b);
    case Fn::hypot: return std::hypot(a, b);
    case Fn::step: return b < a ? Real(0) : Real(1);  // step(edge, x)
    case Fn::copysign: return std::copysign(a, b);
    case Fn::fdim: return std::fdim(a, b);
    case Fn::clamp: return std::fmin(std::fmax(a, b), c);
    case Fn::mix: return a + (b - a) * c;
    case Fn::smoothstep: {  // smoothstep(edge0, edge1, x)
        const Real t = std::fmin(std::fmax((c - a) / (b - a), Real(0)), Real(1));
        return t * t * (Real(3) - Real(2) * t);
    }
    case Fn::mad: return a * b + c;
    }
    return 0;
}

}  // namespace sim::formula
