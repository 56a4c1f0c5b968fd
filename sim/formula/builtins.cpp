#include "sim/formula/builtins.hpp"

#include "sim/formula/rule.hpp"

namespace sim::formula {

namespace {

// The allow-list: OpenCL's math built-ins a formula may call. select() is
// an operation of its own; min and max are fmin and fmax (and for ints the
// same values).
const Builtin table[] = {
    {"sin", 1, Fn::sin},       {"cos", 1, Fn::cos},           {"tan", 1, Fn::tan},       {"asin", 1, Fn::asin},
    {"acos", 1, Fn::acos},     {"atan", 1, Fn::atan},         {"sinh", 1, Fn::sinh},     {"cosh", 1, Fn::cosh},
    {"tanh", 1, Fn::tanh},     {"asinh", 1, Fn::asinh},       {"acosh", 1, Fn::acosh},   {"atanh", 1, Fn::atanh},
    {"exp", 1, Fn::exp},       {"exp2", 1, Fn::exp2},         {"exp10", 1, Fn::exp10},   {"expm1", 1, Fn::expm1},
    {"log", 1, Fn::log},       {"log2", 1, Fn::log2},         {"log10", 1, Fn::log10},   {"log1p", 1, Fn::log1p},
    {"sqrt", 1, Fn::sqrt},     {"rsqrt", 1, Fn::rsqrt},       {"cbrt", 1, Fn::cbrt},     {"fabs", 1, Fn::fabs},
    {"floor", 1, Fn::floor},   {"ceil", 1, Fn::ceil},         {"round", 1, Fn::round},   {"trunc", 1, Fn::trunc},
    {"rint", 1, Fn::rint},     {"sign", 1, Fn::sign},         {"degrees", 1, Fn::degrees}, {"radians", 1, Fn::radians},
    {"abs", 1, Fn::abs_int},   {"pow", 2, Fn::pow},           {"powr", 2, Fn::pow},      {"atan2", 2, Fn::atan2},
    {"fmin", 2, Fn::fmin},     {"fmax", 2, Fn::fmax},         {"min", 2, Fn::fmin},      {"max", 2, Fn::fmax},
    {"fmod", 2, Fn::fmod},     {"hypot", 2, Fn::hypot},       {"step", 2, Fn::step},     {"copysign", 2, Fn::copysign},
    {"fdim", 2, Fn::fdim},     {"clamp", 3, Fn::clamp},       {"mix", 3, Fn::mix},       {"smoothstep", 3, Fn::smoothstep},
    {"mad", 3, Fn::mad},       {"fma", 3, Fn::mad},
};

}  // namespace

const Builtin* find_builtin(const std::string& name) {
    for (const Builtin& b : table)
        if (name == b.name) return &b;
    return nullptr;
}

bool is_builtin_function(const std::string& name) {
    return find_builtin(name) != nullptr;
}

}  // namespace sim::formula
