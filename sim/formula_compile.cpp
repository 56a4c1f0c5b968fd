// A formula's tree compiled into row operations (sim/formula_program.hpp).
//
// Values are either fixed before the run (folded here, in the model's
// number type, so that a folded operation gives what the run would) or
// vary over the cells (a register). Ready's keywords are made on first use:
// a neighbour (a_ne2) is an input at its offset, a stencil (laplacian_a)
// the weighted sum Ready writes for it, in its order of operations.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <cctype>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sim/formula.hpp"
#include "sim/formula_ast.hpp"
#include "sim/formula_program.hpp"
#include "sim/formula_scalar.hpp"

namespace sim::formula {

namespace {

// ---- Ready's stencils (its src/readybase/stencils.cpp, as data) ----

struct StencilPoint {
    int x, y, z, weight;
};

struct Stencil {
    std::string label;
    std::vector<StencilPoint> points;  // in Ready's order: rows north to south, columns west to east
    int divisor = 1, dx_power = 0;
};

Stencil from_1d(const std::string& label, const std::vector<int>& weights, int divisor, int dx_power, int axis) {
    Stencil s{label, {}, divisor, dx_power};
    const int half = static_cast<int>(weights.size() - 1) / 2;
    for (int i = 0; i < static_cast<int>(weights.size()); ++i)
        if (weights[i] != 0) {
            int offset[3] = {0, 0, 0};
            offset[axis] = i - half;
            s.points.push_back({offset[0], offset[1], offset[2], weights[i]});
        }
    return s;
}

// Rows in reading order: the first is the northmost (y + half).
Stencil from_2d(const std::string& label, const std::vector<std::vector<int>>& rows, int divisor, int dx_power) {
    Stencil s{label, {}, divisor, dx_power};
    const int m = static_cast<int>(rows.size()), n = static_cast<int>(rows.front().size());
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i)
            if (rows[j][i] != 0) s.points.push_back({i - (n - 1) / 2, -j + (m - 1) / 2, 0, rows[j][i]});
    return s;
}

std::vector<std::vector<int>> symmetric_3x3(int c1, int c2, int c3) {
    return {{c1, c2, c1}, {c2, c3, c2}, {c1, c2, c1}};
}

std::vector<std::vector<int>> symmetric_5x5(int c1, int c2, int c3, int c4, int c5, int c6) {
    return {{c1, c2, c3, c2, c1}, {c2, c4, c5, c4, c2}, {c3, c5, c6, c5, c3}, {c2, c4, c5, c4, c2}, {c1, c2, c3, c2, c1}};
}

// Ready's 2-D stencils at an accuracy.
std::vector<Stencil> stencils(Accuracy accuracy) {
    const bool high = accuracy == Accuracy::high;
    std::vector<Stencil> s;
    const char* axes[3] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis) {
        const std::string a = axes[axis];
        if (high) {
            s.push_back(from_1d(a + "_gradient", {1, -8, 0, 8, -1}, 12, 1, axis));
            s.push_back(from_1d(a + "_deriv2", {-1, 16, -30, 16, -1}, 12, 2, axis));
            s.push_back(from_1d(a + "_deriv3", {1, -8, 13, 0, -13, 8, -1}, 8, 3, axis));
        } else {
            s.push_back(from_1d(a + "_gradient", {-1, 0, 1}, 2, 1, axis));
            s.push_back(from_1d(a + "_deriv2", {1, -2, 1}, 1, 2, axis));
            s.push_back(from_1d(a + "_deriv3", {-1, 2, 0, -2, 1}, 2, 3, axis));
        }
    }
    s.push_back(from_2d("gaussian", symmetric_5x5(1, 4, 7, 16, 26, 41), 273, 0));
    switch (accuracy) {
    case Accuracy::low: s.push_back(from_2d("laplacian", symmetric_3x3(0, 1, -4), 1, 2)); break;
    case Accuracy::medium: s.push_back(from_2d("laplacian", symmetric_3x3(1, 4, -20), 6, 2)); break;
    case Accuracy::high: s.push_back(from_2d("laplacian", symmetric_5x5(0, -2, -1, 16, 52, -252), 60, 2)); break;
    }
    s.push_back(from_2d("bilaplacian", symmetric_5x5(0, 1, 1, -2, -10, 36), 3, 4));
    s.push_back(from_2d("trilaplacian",
                        {{0, 1, 5, 6, 5, 1, 0},
                         {1, 6, -33, -56, -33, 6, 1},
                         {5, -33, 6, 314, 6, -33, 5},
                         {6, -56, 314, -888, 314, -56, 6},
                         {5, -33, 6, 314, 6, -33, 5},
                         {1, 6, -33, -56, -33, 6, 1},
                         {0, 1, 5, 6, 5, 1, 0}},
                        18, 6));
    s.push_back(from_2d("sobelN", {{1, 2, 1}, {0, 0, 0}, {-1, -2, -1}}, 1, 0));
    s.push_back(from_2d("sobelS", {{-1, -2, -1}, {0, 0, 0}, {1, 2, 1}}, 1, 0));
    s.push_back(from_2d("sobelE", {{-1, 0, 1}, {-2, 0, 2}, {-1, 0, 1}}, 1, 0));
    s.push_back(from_2d("sobelW", {{1, 0, -1}, {2, 0, -2}, {1, 0, -1}}, 1, 0));
    s.push_back(from_2d("sobelNW", {{2, 1, 0}, {1, 0, -1}, {0, -1, -2}}, 1, 0));
    s.push_back(from_2d("sobelNE", {{0, 1, 2}, {-1, 0, 1}, {-2, -1, 0}}, 1, 0));
    s.push_back(from_2d("sobelSW", {{0, -1, -2}, {1, 0, -1}, {2, 1, 0}}, 1, 0));
    s.push_back(from_2d("sobelSE", {{-2, -1, 0}, {-1, 0, 1}, {0, 1, 2}}, 1, 0));
    return s;
}

// ---- built-in functions ----

struct Builtin {
    const char* name;
    int arity;
    Fn fn;
};

// The allow-list: OpenCL's math built-ins a formula may call. select() is
// an operation of its own; min and max are fmin and fmax (and for ints the
// same values).
const Builtin builtins[] = {
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

const Builtin* find_builtin(const std::string& name) {
    for (const Builtin& b : builtins)
        if (name == b.name) return &b;
    return nullptr;
}

// ---- values ----

struct Value {
    bool fixed = true;     // known before the run: `constant`; else register `reg`
    double constant = 0;   // rounded to an int or to the number type
    int reg = -1;
    bool integer = false;  // an int
    bool vector = false;   // a float4 of Ready's blocks (comparisons give -1 for true)
};

struct Variable {
    Type type = Type::real;
    bool is_const = false;
    std::string why_const;        // for errors: "a parameter", "a neighbour", ...
    std::vector<Value> elements;  // one, or an array's
    bool array = false;
    int mask = -1;                // the mask register it was declared under (-1: none)
};

class Compiler {
public:
    explicit Compiler(const Rule& rule) : rule_(rule) {
        for (const Stencil& s : stencils(rule.accuracy)) stencils_[s.label] = s;
    }

    Program compile(const Formula& formula) {
        scopes_.emplace_back();
        for (const StmtPtr& s : formula.statements) statement(*s, all_cells());
        // The forward Euler step of every chemical.
        const Value timestep = lookup_value("timestep", {1, 1});
        for (int i = 0; i < rule_.chemicals; ++i) {
            const std::string chem = chemical_name(i);
            const Value x = lookup_value(chem, {1, 1}), delta = lookup_value("delta_" + chem, {1, 1});
            Value next = arith(Op::add, x, arith(Op::mul, timestep, delta, {}), {});
            program_.outputs.push_back(materialise(next));
        }
        finish();
        return std::move(program_);
    }

private:
    // ---- numbers ----

    double round_real(double x) const {
        return rule_.double_precision ? x : static_cast<double>(static_cast<float>(x));
    }
    static double round_int(double x) {  // C's conversion to a 32-bit int, wrapping as the hardware does
        if (!std::isfinite(x) || std::fabs(x) >= 9.0e18) return 0;
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::int64_t>(std::trunc(x))));
    }
    Value constant(double x, bool integer, bool vector = false) const {
        Value v;
        v.constant = integer ? round_int(x) : round_real(x);
        v.integer = integer;
        v.vector = vector;
        return v;
    }
    Value all_cells() const { return constant(1, true); }
    bool is_all(const Value& mask) const { return mask.fixed && mask.constant != 0; }

    static Instr instruction(Op op) {
        Instr in;
        in.op = op;
        return in;
    }

    int new_register() {
        if (program_.registers >= Limits::max_operations * 2)
            throw FormulaError({1, 1}, "the formula compiles to more than " +
                                           std::to_string(Limits::max_operations) + " operations");
        return program_.registers++;
    }
    int emit(Instr instr) {
        // The same operation on the same registers is the same value.
        const auto key = std::make_tuple(static_cast<int>(instr.op), static_cast<int>(instr.fn), instr.a, instr.b,
                                         instr.c, instr.truth, instr.mask);
        if (instr.op != Op::stencil) {
            auto seen = emitted_.find(key);
            if (seen != emitted_.end()) return seen->second;
        }
        if (static_cast<int>(program_.code.size()) >= Limits::max_operations)
            throw FormulaError(instr.pos, "the formula compiles to more than " +
                                              std::to_string(Limits::max_operations) + " operations");
        instr.dst = new_register();
        program_.code.push_back(instr);
        if (instr.op != Op::stencil) emitted_[key] = instr.dst;
        return instr.dst;
    }
    // A register holding v (a constant's register, made once per value).
    int materialise(const Value& v) {
        if (!v.fixed) return v.reg;
        const auto key = std::make_pair(v.constant, std::signbit(v.constant));
        auto it = constant_regs_.find(key);
        if (it != constant_regs_.end()) return it->second;
        const int reg = new_register();
        program_.constants.push_back({reg, v.constant});
        constant_regs_[key] = reg;
        return reg;
    }
    Value in_register(int reg, bool integer, bool vector) const {
        Value v;
        v.fixed = false;
        v.reg = reg;
        v.integer = integer;
        v.vector = vector;
        return v;
    }
    Value as_real(const Value& v) const {
        if (!v.integer) return v;
        Value r = v;
        r.integer = false;
        if (r.fixed) r.constant = round_real(v.constant);
        return r;  // an int in a register is held as a number already
    }
    Value as_int(const Value& v, Pos pos) {
        if (v.integer) return v;
        if (v.fixed) return constant(v.constant, true, v.vector);
        Instr in = instruction(Op::trunc_int);
        in.a = v.reg;
        in.pos = pos;
        return in_register(emit(in), true, v.vector);
    }

    double truth(const Value& a, const Value& b) const {
        return rule_.block_x == 4 && (a.vector || b.vector) ? -1.0 : 1.0;
    }

    // a op b, folded when both are fixed.
    Value arith(Op op, Value a, Value b, Pos pos) {
        const bool integer = a.integer && b.integer;
        const bool vector = a.vector || b.vector;
        if (!integer) a = as_real(a), b = as_real(b);
        if (op == Op::int_mod && !integer) throw FormulaError(pos, "% takes ints; use fmod for numbers");
        if (integer && op == Op::div) op = Op::int_div;
        // x * 1, 1 * x, x / 1 and x - (+0) are x, bit for bit.
        if (!integer) {
            const auto is = [](const Value& v, double x) {
                return v.fixed && v.constant == x && !std::signbit(v.constant);
            };
            Value same;
            bool found = true;
            if (op == Op::mul && is(b, 1)) same = a;
            else if (op == Op::mul && is(a, 1)) same = b;
            else if ((op == Op::div && is(b, 1)) || (op == Op::sub && is(b, 0))) same = a;
            else found = false;
            if (found && !(a.fixed && b.fixed)) {
                same.vector = vector;
                return same;
            }
        }
        if (a.fixed && b.fixed) {
            if ((op == Op::div || op == Op::int_div || op == Op::int_mod) && b.constant == 0)
                throw FormulaError(pos, "division by zero");
            const double folded = integer ? fold_int(op, a.constant, b.constant)
                                          : fold_real(op, a.constant, b.constant, truth(a, b));
            return constant(folded, integer || is_comparison(op), vector);
        }
        Instr in = instruction(op);
        in.a = materialise(a);
        in.b = materialise(b);
        in.pos = pos;
        in.truth = truth(a, b);
        in.mask = division_mask_;
        return in_register(emit(in), integer || is_comparison(op), vector);
    }
    static bool is_comparison(Op op) {
        return op == Op::less || op == Op::less_equal || op == Op::equal || op == Op::not_equal ||
               op == Op::logical_and || op == Op::logical_or;
    }
    static double fold_int(Op op, double a, double b) {
        const auto x = static_cast<std::int64_t>(a), y = static_cast<std::int64_t>(b);
        switch (op) {
        case Op::add: return static_cast<double>(x + y);
        case Op::sub: return static_cast<double>(x - y);
        case Op::mul: return static_cast<double>(x * y);
        case Op::int_div: return static_cast<double>(x / y);
        case Op::int_mod: return static_cast<double>(x % y);
        case Op::less: return x < y;
        case Op::less_equal: return x <= y;
        case Op::equal: return x == y;
        case Op::not_equal: return x != y;
        case Op::logical_and: return x != 0 && y != 0;
        case Op::logical_or: return x != 0 || y != 0;
        default: return 0;
        }
    }
    double fold_real(Op op, double a, double b, double t) const {
        if (rule_.double_precision) return scalar_op<double>(op, a, b, t);
        return scalar_op<float>(op, static_cast<float>(a), static_cast<float>(b), static_cast<float>(t));
    }
    double fold_call(Fn fn, const std::vector<double>& args) const {
        if (rule_.double_precision) return scalar_call<double>(fn, args[0], args.size() > 1 ? args[1] : 0,
                                                               args.size() > 2 ? args[2] : 0);
        return scalar_call<float>(fn, static_cast<float>(args[0]), static_cast<float>(args.size() > 1 ? args[1] : 0),
                                  static_cast<float>(args.size() > 2 ? args[2] : 0));
    }

    Value select(const Value& if_false, const Value& if_true, const Value& condition, Pos pos) {
        if (condition.fixed) return condition.constant != 0 ? if_true : if_false;
        const bool integer = if_false.integer && if_true.integer;
        const Value f = integer ? if_false : as_real(if_false), t = integer ? if_true : as_real(if_true);
        if (f.fixed && t.fixed && f.constant == t.constant && std::signbit(f.constant) == std::signbit(t.constant))
            return f;
        Instr in = instruction(Op::select);
        in.a = materialise(f);
        in.b = materialise(t);
        in.c = condition.reg;
        in.pos = pos;
        return in_register(emit(in), integer, f.vector || t.vector || condition.vector);
    }
    // nonzero -> 1: a mask.
    Value logical_and(const Value& a, const Value& b, Pos pos) {
        if (a.fixed) return a.constant != 0 ? truthy(b, pos) : constant(0, true);
        if (b.fixed) return b.constant != 0 ? truthy(a, pos) : constant(0, true);
        Instr in = instruction(Op::logical_and);
        in.a = a.reg;
        in.b = b.reg;
        in.pos = pos;
        return in_register(emit(in), true, false);
    }
    Value truthy(const Value& v, Pos pos) {
        if (v.fixed) return constant(v.constant != 0, true);
        Instr in = instruction(Op::not_equal);
        in.a = v.reg;
        in.b = materialise(constant(0, v.integer));
        in.pos = pos;
        return in_register(emit(in), true, false);
    }
    Value logical_not(const Value& v, Pos pos) {
        if (v.fixed) return constant(v.constant == 0 ? (rule_.block_x == 4 && v.vector ? -1 : 1) : 0, true, v.vector);
        Instr in = instruction(Op::logical_not);
        in.a = v.reg;
        in.truth = rule_.block_x == 4 && v.vector ? -1 : 1;
        in.pos = pos;
        return in_register(emit(in), true, v.vector);
    }

    // ---- names ----

    Variable* find_variable(const std::string& name) {
        for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope) {
            auto it = scope->find(name);
            if (it != scope->end()) return &it->second;
        }
        auto it = predefined_.find(name);
        if (it != predefined_.end()) return &it->second;
        return make_predefined(name);
    }

    std::string chemical_of(const std::string& name) const {
        for (int i = 0; i < rule_.chemicals; ++i)
            if (name == chemical_name(i)) return name;
        return "";
    }

    Value input(int chemical, int dx, int dy) {
        const auto key = std::make_tuple(chemical, dx, dy);
        auto it = inputs_.find(key);
        if (it != inputs_.end()) return it->second;
        const int reg = new_register();
        program_.inputs.push_back({reg, chemical, dx, dy});
        program_.radius_x = std::max(program_.radius_x, std::abs(dx));
        program_.radius_y = std::max(program_.radius_y, std::abs(dy));
        const Value v = in_register(reg, false, rule_.block_x == 4);
        inputs_[key] = v;
        return v;
    }

    Variable constant_variable(const Value& v, const std::string& why) const {
        Variable var;
        var.is_const = true;
        var.why_const = why;
        var.elements = {v};
        return var;
    }

    // Ready's keywords, made on first use; nullptr for an unknown name.
    Variable* make_predefined(const std::string& name) {
        for (int i = 0; i < rule_.chemicals; ++i) {
            const std::string chem = chemical_name(i);
            if (name == chem) {
                Variable var;
                var.type = Type::real4;
                var.elements = {input(i, 0, 0)};
                return &(predefined_[name] = var);
            }
            if (name == "delta_" + chem) {
                Variable var;
                var.type = Type::real4;
                var.elements = {constant(0, false, rule_.block_x == 4)};
                return &(predefined_[name] = var);
            }
        }
        for (const auto& [parameter, value] : rule_.parameters)
            if (name == parameter) {
                // Ready holds parameters as float and writes them into its
                // kernel with 8 decimals: in a double rule 1.1 is 1.10000002.
                char text[64];
                std::snprintf(text, sizeof text, "%.8f", static_cast<double>(static_cast<float>(value)));
                return &(predefined_[name] = constant_variable(constant(std::strtod(text, nullptr), false),
                                                                "a parameter of the rule"));
            }
        if (name == "dx") return &(predefined_[name] = constant_variable(constant(1, false), "the grid spacing"));
        if (name == "x_pos" || name == "y_pos") {
            const int reg = new_register();
            (name == "x_pos" ? program_.x_pos : program_.y_pos) = reg;
            return &(predefined_[name] =
                         constant_variable(in_register(reg, false, rule_.block_x == 4), "the cell's position"));
        }
        if (name == "z_pos")
            return &(predefined_[name] = constant_variable(constant(0, false, rule_.block_x == 4), "the cell's position"));
        if (name == "M_PI" || name == "M_PI_F")
            return &(predefined_[name] = constant_variable(constant(3.14159265358979323846, false), "a constant"));
        if (name == "M_E" || name == "M_E_F")
            return &(predefined_[name] = constant_variable(constant(2.71828182845904523536, false), "a constant"));
        // A neighbour: chemical, then u/d, n/s and e/w each with a count
        // (Ready's names: a_n, a_se, a_e2, a_n2w3; u and d, the same cell
        // on a 2-D grid).
        if (name.size() > 2 && name[1] == '_' && !chemical_of(name.substr(0, 1)).empty()) {
            std::size_t at = 2;
            int offset[3] = {0, 0, 0};  // z, y, x
            bool good = true, any = false;
            const char* letters[3][2] = {{"u", "d"}, {"n", "s"}, {"e", "w"}};
            for (int axis = 0; axis < 3 && good; ++axis) {
                if (at >= name.size()) break;
                const char c = name[at];
                const int sign = c == letters[axis][0][0] ? 1 : c == letters[axis][1][0] ? -1 : 0;
                if (sign == 0) continue;
                ++at;
                std::size_t digits = at;
                while (digits < name.size() && std::isdigit(static_cast<unsigned char>(name[digits]))) ++digits;
                int count = 1;
                if (digits > at) {
                    const std::string number = name.substr(at, digits - at);
                    // Ready writes a_n, never a_n1; at most 10 cells away.
                    if (number.size() > 2 || number[0] == '0' || number == "1") good = false;
                    else count = std::atoi(number.c_str());
                }
                at = digits;
                offset[axis] = sign * count;
                any = true;
            }
            if (good && any && at == name.size() && std::abs(offset[0]) <= 10 && std::abs(offset[1]) <= 10 &&
                std::abs(offset[2]) <= 10) {
                const int chem = name[0] - 'a';
                return &(predefined_[name] =
                             constant_variable(input(chem, offset[2], offset[1]), "a neighbour's value"));
            }
        }
        // A stencil: label_chemical.
        const std::size_t underscore = name.rfind('_');
        if (underscore != std::string::npos) {
            const std::string label = name.substr(0, underscore), chem = name.substr(underscore + 1);
            if (!chemical_of(chem).empty()) {
                const int c = chem[0] - 'a';
                if (stencils_.count(label))
                    return &(predefined_[name] = constant_variable(apply_stencil(stencils_.at(label), c),
                                                                    "a stencil of the rule's chemicals"));
                if (label == "gradient_mag_squared") {
                    // pow(x_gradient, 2) + pow(y_gradient, 2), as Ready writes it.
                    const Value two = constant(2, false);
                    const Value gx = call(Fn::pow, {apply_stencil(stencils_.at("x_gradient"), c), two}, {});
                    const Value gy = call(Fn::pow, {apply_stencil(stencils_.at("y_gradient"), c), two}, {});
                    return &(predefined_[name] =
                                 constant_variable(arith(Op::add, gx, gy, {}), "a stencil of the rule's chemicals"));
                }
            }
        }
        return nullptr;
    }

    // (w1 * (p + p ...) + p + ... + w2 * p) / (divisor * dx * dx ...), the
    // weights in ascending order, as Ready's AppliedStencil::GetCode writes
    // it: one operation (Op::stencil) that keeps that order.
    Value apply_stencil(const Stencil& s, int chemical) {
        std::map<int, std::vector<StencilPoint>> by_weight;
        for (const StencilPoint& p : s.points) by_weight[p.weight].push_back(p);
        StencilSum sum;
        bool vector = false;
        for (const auto& [weight, points] : by_weight) {
            if (weight == 1) {
                for (const StencilPoint& p : points) {
                    const Value v = input(chemical, p.x, p.y);
                    vector |= v.vector;
                    sum.terms.push_back({1.0, {v.reg}});
                }
                continue;
            }
            StencilSum::Term term{round_real(weight), {}};
            for (const StencilPoint& p : points) {
                const Value v = input(chemical, p.x, p.y);
                vector |= v.vector;
                term.inputs.push_back(v.reg);
            }
            sum.terms.push_back(std::move(term));
        }
        if (s.divisor != 1 || s.dx_power > 0) {
            Value divisor = constant(s.divisor, true);
            const Value dx = keyword("dx");
            for (int i = 0; i < s.dx_power; ++i) divisor = arith(Op::mul, divisor, dx, {});
            divisor = as_real(divisor);
            if (divisor.constant == 0) throw FormulaError({1, 1}, "dx is 0: the stencils divide by it");
            sum.divide = true;
            sum.divisor = divisor.constant;
        }
        Instr in = instruction(Op::stencil);
        in.a = static_cast<int>(program_.stencils.size());
        program_.stencils.push_back(std::move(sum));
        return in_register(emit(in), false, vector);
    }

    // A keyword of the rule, whatever the formula declares.
    Value keyword(const std::string& name) {
        auto it = predefined_.find(name);
        Variable* var = it != predefined_.end() ? &it->second : make_predefined(name);
        return var->elements.front();
    }

    Value lookup_value(const std::string& name, Pos pos) {
        Variable* var = find_variable(name);
        if (!var) throw FormulaError(pos, "'" + name + "' is not a chemical, parameter, keyword or variable here");
        if (var->array) throw FormulaError(pos, "'" + name + "' is an array: give an index");
        return var->elements.front();
    }

    // ---- expressions ----

    Value call(Fn fn, std::vector<Value> args, Pos pos) {
        bool vector = false, integer = true, fixed = true;
        for (const Value& a : args) vector |= a.vector, integer &= a.integer, fixed &= a.fixed;
        if (fn == Fn::abs_int && !integer) throw FormulaError(pos, "abs takes ints; use fabs for numbers");
        const bool int_result = integer && (fn == Fn::abs_int || fn == Fn::fmin || fn == Fn::fmax || fn == Fn::clamp);
        if (!int_result)
            for (Value& a : args) a = as_real(a);
        if (fixed) {
            std::vector<double> values;
            for (const Value& a : args) values.push_back(a.constant);
            const double folded = int_result ? fold_int_call(fn, values) : fold_call(fn, values);
            return constant(folded, int_result, vector);
        }
        Instr in = instruction(args.size() == 1 ? Op::call1 : args.size() == 2 ? Op::call2 : Op::call3);
        in.fn = fn;
        in.a = materialise(args[0]);
        if (args.size() > 1) in.b = materialise(args[1]);
        if (args.size() > 2) in.c = materialise(args[2]);
        in.pos = pos;
        return in_register(emit(in), int_result, vector);
    }
    static double fold_int_call(Fn fn, const std::vector<double>& v) {
        switch (fn) {
        case Fn::abs_int: return std::fabs(v[0]);
        case Fn::fmin: return std::min(v[0], v[1]);
        case Fn::fmax: return std::max(v[0], v[1]);
        case Fn::clamp: return std::min(std::max(v[0], v[1]), v[2]);
        default: return 0;
        }
    }

    Value expression(const Expr& e) {
        switch (e.kind) {
        case Expr::Kind::number: return constant(e.value, e.integer);
        case Expr::Kind::name: return lookup_value(e.text, e.pos);
        case Expr::Kind::index: {
            Variable* var = find_variable(e.text);
            if (!var) throw FormulaError(e.pos, "'" + e.text + "' is not an array here");
            if (!var->array) throw FormulaError(e.pos, "'" + e.text + "' is not an array");
            return var->elements[element(*var, e)];
        }
        case Expr::Kind::call: {
            if (e.text == "select") {
                if (e.args.size() != 3) throw FormulaError(e.pos, "select takes 3 arguments");
                // select(a, b, c) is c ? b : a, both computed: a division in
                // the one not taken gives a value that is thrown away, as in
                // OpenCL, so each is checked only on the cells that take it.
                const Value c = expression(*e.args[2]);
                if (c.fixed) {
                    const Value a = expression(*e.args[0]), b = expression(*e.args[1]);
                    return select(a, b, c, e.pos);
                }
                const Value yes = truthy(c, e.pos), outer = division_mask();
                Value a, b;
                {
                    const DivisionMask divisions(*this, logical_and(outer, logical_not_mask(c, e.pos), e.pos));
                    a = expression(*e.args[0]);
                }
                {
                    const DivisionMask divisions(*this, logical_and(outer, yes, e.pos));
                    b = expression(*e.args[1]);
                }
                return select(a, b, yes, e.pos);
            }
            // OpenCL's relational built-ins: the comparisons as functions.
            static const std::pair<const char*, const char*> relations[] = {
                {"isgreater", ">"}, {"isgreaterequal", ">="}, {"isless", "<"},
                {"islessequal", "<="}, {"isequal", "=="},      {"isnotequal", "!="}};
            for (const auto& [name, op] : relations) {
                if (e.text != name) continue;
                if (e.args.size() != 2) throw FormulaError(e.pos, e.text + " takes 2 arguments");
                const Value a = expression(*e.args[0]), b = expression(*e.args[1]);
                const std::string o = op;
                if (o == ">") return arith(Op::less, b, a, e.pos);
                if (o == ">=") return arith(Op::less_equal, b, a, e.pos);
                if (o == "<") return arith(Op::less, a, b, e.pos);
                if (o == "<=") return arith(Op::less_equal, a, b, e.pos);
                return arith(o == "==" ? Op::equal : Op::not_equal, a, b, e.pos);
            }
            const Builtin* b = find_builtin(e.text);
            if (!b) {
                if (find_variable(e.text)) throw FormulaError(e.pos, "'" + e.text + "' is not a function");
                throw FormulaError(e.pos, "'" + e.text + "' is not a function figgen allows (see docs/formulas.md)");
            }
            if (static_cast<int>(e.args.size()) != b->arity)
                throw FormulaError(e.pos, e.text + " takes " + std::to_string(b->arity) + " argument" +
                                              (b->arity == 1 ? "" : "s") + ", not " + std::to_string(e.args.size()));
            std::vector<Value> args;
            for (const ExprPtr& a : e.args) args.push_back(expression(*a));
            return call(b->fn, std::move(args), e.pos);
        }
        case Expr::Kind::cast: {
            const Value v = expression(*e.args[0]);
            if (e.type == Type::integer) return as_int(v, e.pos);
            Value r = as_real(v);
            r.vector = r.vector || (e.type == Type::real4 && rule_.block_x == 4);
            return r;
        }
        case Expr::Kind::unary: {
            const Value v = expression(*e.args[0]);
            if (e.text == "+") return v;
            if (e.text == "!") return logical_not(v, e.pos);
            if (v.fixed) return constant(-v.constant, v.integer, v.vector);
            Instr in = instruction(Op::neg);
            in.a = v.reg;
            in.pos = e.pos;
            return in_register(emit(in), v.integer, v.vector);
        }
        case Expr::Kind::binary: {
            const Value a = expression(*e.args[0]), b = expression(*e.args[1]);
            const std::string& op = e.text;
            if (op == "+") return arith(Op::add, a, b, e.pos);
            if (op == "-") return arith(Op::sub, a, b, e.pos);
            if (op == "*") return arith(Op::mul, a, b, e.pos);
            if (op == "/") return arith(Op::div, a, b, e.pos);
            if (op == "%") return arith(Op::int_mod, a, b, e.pos);
            if (op == "<") return arith(Op::less, a, b, e.pos);
            if (op == ">") return arith(Op::less, b, a, e.pos);
            if (op == "<=") return arith(Op::less_equal, a, b, e.pos);
            if (op == ">=") return arith(Op::less_equal, b, a, e.pos);
            if (op == "==") return arith(Op::equal, a, b, e.pos);
            if (op == "!=") return arith(Op::not_equal, a, b, e.pos);
            if (op == "&&") return arith(Op::logical_and, a, b, e.pos);
            if (op == "||") return arith(Op::logical_or, a, b, e.pos);
            throw FormulaError(e.pos, "unknown operator " + op);
        }
        case Expr::Kind::ternary: {
            const Value c = expression(*e.args[0]);
            if (c.fixed) return expression(*e.args[c.constant != 0 ? 1 : 2]);
            const Value yes = truthy(c, e.pos), outer = division_mask();
            Value t, f;
            {
                const DivisionMask divisions(*this, logical_and(outer, yes, e.pos));
                t = expression(*e.args[1]);
            }
            {
                const DivisionMask divisions(*this, logical_and(outer, logical_not_mask(c, e.pos), e.pos));
                f = expression(*e.args[2]);
            }
            return select(f, t, yes, e.pos);
        }
        }
        throw FormulaError(e.pos, "unknown expression");
    }

    // The fixed index of an array element.
    int element(const Variable& var, const Expr& e) {
        const Value index = expression(*e.args[0]);
        if (!index.fixed)
            throw FormulaError(e.args[0]->pos, "an array index must be known before the run, not vary over the cells");
        if (!index.integer) throw FormulaError(e.args[0]->pos, "an array index must be an int");
        const double i = index.constant;
        if (i < 0 || i >= static_cast<double>(var.elements.size()))
            throw FormulaError(e.args[0]->pos, "index " + std::to_string(static_cast<long long>(i)) + " is outside '" +
                                                   e.text + "[" + std::to_string(var.elements.size()) + "]'");
        return static_cast<int>(i);
    }

    // ---- statements ----

    Value converted(const Value& v, Type type, Pos pos) {
        if (type == Type::integer) return as_int(v, pos);
        Value r = as_real(v);
        if (type == Type::real4 && rule_.block_x == 4) r.vector = true;
        return r;
    }

    void count_statement(Pos pos) {
        if (++statements_run_ > Limits::max_unrolled)
            throw FormulaError(pos, "the formula runs more than " + std::to_string(Limits::max_unrolled) +
                                        " statements once its loops are unrolled");
    }

    // Divisions check for zero only on the cells an `if` or `?:` lets through.
    struct DivisionMask {
        Compiler& c;
        int saved;
        DivisionMask(Compiler& compiler, const Value& mask) : c(compiler), saved(compiler.division_mask_) {
            c.division_mask_ = mask.fixed ? -1 : mask.reg;
        }
        ~DivisionMask() { c.division_mask_ = saved; }
    };
    Value division_mask() const { return division_mask_ < 0 ? all_cells() : in_register(division_mask_, true, false); }

    void statement(const Stmt& s, const Value& mask) {
        count_statement(s.pos);
        const DivisionMask divisions(*this, mask);
        switch (s.kind) {
        case Stmt::Kind::empty: return;
        case Stmt::Kind::block:
            scopes_.emplace_back();
            for (const StmtPtr& inner : s.body) statement(*inner, mask);
            scopes_.pop_back();
            return;
        case Stmt::Kind::declare: declare(s, mask); return;
        case Stmt::Kind::assign: assign(s, mask); return;
        case Stmt::Kind::if_: {
            const Value c = expression(*s.condition);
            if (c.fixed) {
                if (c.constant != 0) statement(*s.body[0], mask);
                else if (s.body.size() > 1) statement(*s.body[1], mask);
                return;
            }
            const Value yes = logical_and(mask, truthy(c, s.condition->pos), s.pos);
            statement(*s.body[0], yes);
            if (s.body.size() > 1) statement(*s.body[1], logical_and(mask, logical_not_mask(c, s.pos), s.pos));
            return;
        }
        case Stmt::Kind::for_: {
            scopes_.emplace_back();
            if (s.init) statement(*s.init, mask);
            for (int trip = 0;; ++trip) {
                if (s.condition) {
                    const Value c = expression(*s.condition);
                    if (!c.fixed)
                        throw FormulaError(s.condition->pos,
                                           "a loop's condition must be known before the run, not vary over the cells");
                    if (c.constant == 0) break;
                } else {
                    throw FormulaError(s.pos, "a loop needs a condition that ends it");
                }
                if (trip >= 4096)
                    throw FormulaError(s.pos, "a loop of more than 4096 trips");
                scopes_.emplace_back();
                statement(*s.body[0], mask);
                scopes_.pop_back();
                if (s.step) statement(*s.step, mask);
            }
            scopes_.pop_back();
            return;
        }
        }
    }
    Value logical_not_mask(const Value& c, Pos pos) {  // 1 where c is zero
        Instr in = instruction(Op::logical_not);
        in.a = c.reg;
        in.pos = pos;
        return in_register(emit(in), true, false);
    }

    void declare(const Stmt& s, const Value& mask) {
        auto& scope = scopes_.back();
        for (const Declarator& d : s.declarators) {
            if (scope.count(d.name)) throw FormulaError(d.pos, "'" + d.name + "' is declared twice");
            if (scopes_.size() == 1 && (predefined_.count(d.name) || make_predefined(d.name)))
                throw FormulaError(d.pos, "'" + d.name + "' is already a chemical, parameter or keyword of the rule");
            Variable var;
            var.type = s.type;
            var.is_const = s.is_const;
            var.why_const = "declared const";
            var.mask = mask.fixed ? -1 : mask.reg;
            const Value zero = converted(constant(0, s.type == Type::integer), s.type, d.pos);
            if (d.array_size > 0) {
                if (d.init) throw FormulaError(d.init->pos, "an array cannot be given a value as a whole");
                var.array = true;
                var.elements.assign(static_cast<std::size_t>(d.array_size), zero);
            } else {
                if (!d.init && s.is_const) throw FormulaError(d.pos, "a const needs a value");
                // An uninitialised variable reads as zero (OpenCL leaves it undefined).
                var.elements = {d.init ? converted(expression(*d.init), s.type, d.init->pos) : zero};
            }
            scope[d.name] = std::move(var);
        }
    }

    void assign(const Stmt& s, const Value& mask) {
        const Expr& target = *s.target;
        Variable* var = find_variable(target.text);
        if (!var) throw FormulaError(target.pos, "'" + target.text + "' is not declared");
        if (var->is_const) throw FormulaError(target.pos, "'" + target.text + "' is " + var->why_const + ": it cannot be assigned");
        int index = 0;
        if (target.kind == Expr::Kind::index) {
            if (!var->array) throw FormulaError(target.pos, "'" + target.text + "' is not an array");
            index = element(*var, target);
        } else if (var->array) {
            throw FormulaError(target.pos, "'" + target.text + "' is an array: assign its elements");
        }
        const Value old = var->elements[index];
        Value value = expression(*s.value);
        if (s.op == "+=") value = arith(Op::add, old, value, s.value->pos);
        else if (s.op == "-=") value = arith(Op::sub, old, value, s.value->pos);
        else if (s.op == "*=") value = arith(Op::mul, old, value, s.value->pos);
        else if (s.op == "/=") value = arith(Op::div, old, value, s.value->pos);
        value = converted(value, var->type, s.value->pos);
        // Under an `if` on the cells' values, only the cells where it holds change.
        const bool whole = is_all(mask) || var->mask == mask.reg;
        if (!whole) value = select(old, value, mask, s.pos);
        var->elements[index] = value;
    }

    // ---- the program's registers ----

    std::vector<int> sources(const Instr& in) const { return formula::sources(program_, in); }

    // ---- chains (sim/formula_program.hpp's Chain) ----

    // Whether instruction `in` may go into a chain: nothing in it can fail.
    bool chainable(const Instr& in, const std::vector<char>& is_constant, const std::vector<double>& value) const {
        switch (in.op) {
        case Op::stencil: return true;
        case Op::add:
        case Op::sub:
        case Op::mul: return in.a >= 0 && in.b >= 0;
        case Op::div: return in.a >= 0 && in.b >= 0 && is_constant[in.b] && value[in.b] != 0 && !is_constant[in.a];
        default: return false;
        }
    }

    // The SSA code `code` (each register written once) with runs of
    // operations fused into chains: an operation whose value only the next
    // in the chain reads goes into it, and so does a short chain that is
    // one step's operand (as the second accumulator).
    std::vector<Instr> fuse(const std::vector<Instr>& code) {
        const int n = program_.registers;
        const int count = static_cast<int>(code.size());
        std::vector<char> is_constant(static_cast<std::size_t>(n), 0);
        std::vector<double> value(static_cast<std::size_t>(n), 0);
        for (const Program::Constant& c : program_.constants) {
            is_constant[c.reg] = 1;
            value[c.reg] = c.value;
        }
        std::vector<int> def(static_cast<std::size_t>(n), -1), uses(static_cast<std::size_t>(n), 0);
        for (int i = 0; i < count; ++i) {
            def[code[i].dst] = i;
            for (int r : sources(code[i])) ++uses[r];
        }
        for (int out : program_.outputs) ++uses[out];
        std::vector<char> can(static_cast<std::size_t>(count), 0);
        for (int i = 0; i < count; ++i) can[i] = chainable(code[i], is_constant, value);
        // through[i]: the operand (a or b) whose chain instruction i
        // continues, or -1; length[i]: the chain's operations up to i.
        std::vector<int> through(static_cast<std::size_t>(count), -1), length(static_cast<std::size_t>(count), 1);
        std::vector<char> interior(static_cast<std::size_t>(count), 0);
        for (int i = 0; i < count; ++i) {
            const Instr& in = code[i];
            if (!can[i] || in.op == Op::stencil || in.a == in.b) continue;
            int best = -1;
            for (int r : {in.a, in.b}) {
                if (in.op == Op::div && r != in.a) continue;  // the divisor is the constant
                const int d = def[r];
                if (d < 0 || !can[d] || uses[r] != 1 || interior[d]) continue;
                if (best < 0 || length[d] > length[def[best]]) best = r;
            }
            if (best < 0) continue;
            through[i] = best;
            interior[def[best]] = 1;
            length[i] = length[def[best]] + 1;
        }
        // The path of a chain's operations, from its head to `root`.
        auto path = [&](int root) {
            std::vector<int> p{root};
            while (through[p.back()] >= 0) p.push_back(def[through[p.back()]]);
            std::reverse(p.begin(), p.end());
            return p;
        };
        auto other = [&](int i) { return through[i] == code[i].a ? code[i].b : code[i].a; };
        // Short chains taken whole as one step's operand.
        constexpr int aux_most = 4;  // operations of such a chain
        std::vector<char> absorbed(static_cast<std::size_t>(count), 0), has_aux(static_cast<std::size_t>(count), 0);
        std::vector<char> has_stencil(static_cast<std::size_t>(count), 0);
        for (int i = 0; i < count; ++i)
            has_stencil[i] = code[i].op == Op::stencil || (through[i] >= 0 && has_stencil[def[through[i]]]);
        for (int root = 0; root < count; ++root) {
            if (!can[root] || interior[root]) continue;
            for (int link : path(root)) {
                if (through[link] < 0) continue;
                const int o = other(link);
                const int d = def[o];
                if (d < 0 || !can[d] || interior[d] || absorbed[d] || uses[o] != 1 || has_stencil[d] || has_aux[d] ||
                    length[d] > aux_most)
                    continue;
                absorbed[d] = 1;
                has_aux[root] = 1;
            }
        }
        auto operand = [&](int reg, int& x, double& k) {
            if (is_constant[reg]) {
                x = -1;
                k = value[reg];
            } else {
                x = reg;
            }
        };
        std::vector<Instr> fused;
        for (int root = 0; root < count; ++root) {
            if (!can[root]) {
                fused.push_back(code[root]);
                continue;
            }
            if (interior[root] || absorbed[root]) continue;
            Chain chain;
            const std::vector<int> steps = path(root);
            // A chain's head, into acc (or aux).
            auto head = [&](int i, bool aux) {
                Chain::Step st;
                const Instr& in = code[i];
                if (in.op == Op::stencil) {
                    st.kind = Chain::Kind::stencil;
                    st.stencil = in.a;
                } else {
                    st.kind = aux ? Chain::Kind::aux : Chain::Kind::binary;
                    st.op = in.op;
                    operand(in.a, st.x, st.kx);
                    operand(in.b, st.y, st.ky);
                }
                chain.steps.push_back(st);
            };
            // A link: the value so far (in acc or aux) with the other operand.
            auto link = [&](int i, Chain::Kind kind) {
                Chain::Step st;
                st.kind = kind;
                st.op = code[i].op;
                st.t_first = through[i] == code[i].a;
                if (kind != Chain::Kind::acc_aux) operand(other(i), st.x, st.kx);
                chain.steps.push_back(st);
            };
            head(steps.front(), false);
            for (std::size_t k = 1; k < steps.size(); ++k) {
                const int i = steps[k];
                const int d = def[other(i)];
                if (d >= 0 && absorbed[d]) {
                    const std::vector<int> side = path(d);
                    head(side.front(), true);
                    for (std::size_t j = 1; j < side.size(); ++j) link(side[j], Chain::Kind::aux_op);
                    link(i, Chain::Kind::acc_aux);
                } else {
                    link(i, Chain::Kind::acc);
                }
            }
            Instr in = code[root];
            in.op = Op::chain;
            in.a = static_cast<int>(program_.chains.size());
            in.b = in.c = in.mask = -1;
            program_.chains.push_back(std::move(chain));
            fused.push_back(in);
        }
        return fused;
    }

    // Dead operations removed; registers renumbered so that buffers are
    // shared by values whose lives do not overlap.
    void finish() {
        const int n = program_.registers;
        std::vector<char> live(static_cast<std::size_t>(n), 0);
        for (int out : program_.outputs) live[out] = 1;
        std::vector<char> keep(program_.code.size(), 0);
        for (int i = static_cast<int>(program_.code.size()) - 1; i >= 0; --i) {
            const Instr& in = program_.code[i];
            if (!live[in.dst]) continue;
            keep[i] = 1;
            for (int r : sources(in)) live[r] = 1;
        }
        std::vector<Instr> code;
        for (std::size_t i = 0; i < keep.size(); ++i)
            if (keep[i]) code.push_back(program_.code[i]);
        program_.operations = static_cast<int>(code.size());
        code = fuse(code);
        std::fill(live.begin(), live.end(), 0);
        for (int out : program_.outputs) live[out] = 1;
        for (const Instr& in : code)
            for (int r : sources(in)) live[r] = 1;
        // Register kinds: inputs and x_pos/y_pos are views; constants filled once.
        std::vector<char> temporary(static_cast<std::size_t>(n), 1);
        for (const Program::Input& in : program_.inputs) temporary[in.reg] = 0;
        for (const Program::Constant& c : program_.constants) temporary[c.reg] = 0;
        for (int pos : {program_.x_pos, program_.y_pos})
            if (pos >= 0) temporary[pos] = 0;
        for (int out : program_.outputs) temporary[out] = 0;
        std::vector<int> map(static_cast<std::size_t>(n), -1);
        int next = 0;
        std::vector<Program::Input> inputs;
        for (const Program::Input& in : program_.inputs)
            if (live[in.reg]) {
                map[in.reg] = next++;
                inputs.push_back({map[in.reg], in.chemical, in.dx, in.dy});
            }
        // radius from the inputs kept
        program_.radius_x = program_.radius_y = 0;
        for (const Program::Input& in : inputs) {
            program_.radius_x = std::max(program_.radius_x, std::abs(in.dx));
            program_.radius_y = std::max(program_.radius_y, std::abs(in.dy));
        }
        for (int* pos : {&program_.x_pos, &program_.y_pos})
            if (*pos >= 0) *pos = live[*pos] ? (map[*pos] = next++) : -1;
        std::vector<Program::Constant> constants;
        for (const Program::Constant& c : program_.constants)
            if (live[c.reg]) {
                map[c.reg] = next++;
                constants.push_back({map[c.reg], c.value});
            }
        // Temporaries: a buffer freed after its last use is taken again.
        std::vector<int> last_use(static_cast<std::size_t>(n), -1);
        for (int i = 0; i < static_cast<int>(code.size()); ++i)
            for (int r : sources(code[i])) last_use[r] = i;
        for (int out : program_.outputs) last_use[out] = static_cast<int>(code.size());
        std::vector<int> free_buffers;
        std::vector<StencilSum> stencils;
        for (int i = 0; i < static_cast<int>(code.size()); ++i) {
            Instr& in = code[i];
            const std::vector<int> read = sources(in);
            // Renumbered: the operands, a chain's operands and its stencils' inputs (in their own copies).
            if (in.op == Op::chain) {
                for (Chain::Step& st : program_.chains[in.a].steps) {
                    for (int* r : {&st.x, &st.y})
                        if (*r >= 0) *r = map[*r];
                    if (st.stencil >= 0) {
                        StencilSum sum = program_.stencils[st.stencil];
                        for (StencilSum::Term& t : sum.terms)
                            for (int& r : t.inputs) r = map[r];
                        st.stencil = static_cast<int>(stencils.size());
                        stencils.push_back(std::move(sum));
                    }
                }
            } else {
                for (int* r : {&in.a, &in.b, &in.c, &in.mask})
                    if (*r >= 0) *r = map[*r];
            }
            for (int virt : read)
                if (last_use[virt] == i && temporary[virt]) {
                    free_buffers.push_back(map[virt]);
                    last_use[virt] = -2;  // freed once
                }
            if (map[in.dst] < 0) {
                if (!free_buffers.empty()) {
                    map[in.dst] = free_buffers.back();
                    free_buffers.pop_back();
                } else {
                    map[in.dst] = next++;
                }
            }
            in.dst = map[in.dst];
        }
        for (int& out : program_.outputs) out = map[out];
        program_.code = std::move(code);
        program_.stencils = std::move(stencils);
        program_.inputs = std::move(inputs);
        program_.constants = std::move(constants);
        program_.registers = next;
    }
    const Rule& rule_;
    std::map<std::string, Stencil> stencils_;
    std::vector<std::unordered_map<std::string, Variable>> scopes_;
    std::unordered_map<std::string, Variable> predefined_;
    std::map<std::tuple<int, int, int>, Value> inputs_;
    std::map<std::pair<double, bool>, int> constant_regs_;
    int division_mask_ = -1;
    std::map<std::tuple<int, int, int, int, int, double, int>, int> emitted_;
    int statements_run_ = 0;
    Program program_;
};

}  // namespace

std::vector<int> sources(const Program& program, const Instr& in) {
    std::vector<int> read;
    auto stencil = [&](int index) {
        for (const StencilSum::Term& t : program.stencils[static_cast<std::size_t>(index)].terms)
            read.insert(read.end(), t.inputs.begin(), t.inputs.end());
    };
    if (in.op == Op::stencil) {
        stencil(in.a);
    } else if (in.op == Op::chain) {
        for (const Chain::Step& st : program.chains[static_cast<std::size_t>(in.a)].steps) {
            if (st.kind == Chain::Kind::stencil) stencil(st.stencil);
            for (int r : {st.x, st.y})
                if (r >= 0) read.push_back(r);
        }
    } else {
        for (int r : {in.a, in.b, in.c, in.mask})
            if (r >= 0) read.push_back(r);
    }
    return read;
}

bool is_builtin_function(const std::string& name) {
    return find_builtin(name) != nullptr;
}

const std::vector<std::string>& stencil_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const Stencil& s : stencils(Accuracy::medium)) n.push_back(s.label);
        n.push_back("gradient_mag_squared");
        return n;
    }();
    return names;
}

Program compile(const Rule& rule, int width, int height) {
    const Formula formula = parse(rule.code);
    (void)width;  // the grid's size shapes nothing of the program yet
    (void)height;
    return Compiler(rule).compile(formula);
}

}  // namespace sim::formula
