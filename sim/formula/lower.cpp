// The lowering: a formula's tree into row operations (sim/formula/program.hpp).
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
#include <stdexcept>
#include <cctype>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sim/formula/builtins.hpp"
#include "sim/formula/passes.hpp"
#include "sim/formula/program.hpp"
#include "sim/formula/rule.hpp"
#include "sim/formula/scalar.hpp"
#include "sim/formula/stencils.hpp"
#include "sim/formula/tree.hpp"

namespace sim::formula {

namespace {

// ---- values ----

struct Product;

struct Value {
    bool fixed = true;     // known before the run: `constant`; else register `reg`
    double constant = 0;   // rounded to an int or to the number type
    int reg = -1;
    bool integer = false;  // an int
    bool vector = false;   // a float4 of Ready's blocks (comparisons give -1 for true)
    // A product made in the expression being lowered (and not yet used): an
    // addition it meets may take its factors instead, as one fused
    // multiply-add (Rule::fused_multiply_add). `negated`: it is -(x * y).
    std::shared_ptr<const Product> product;
    bool negated = false;
};

struct Product {
    Value x, y;
};

// v as a variable holds it: no longer a product of its expression.
Value stored(Value v) {
    v.product.reset();
    v.negated = false;
    return v;
}

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
    Compiler(const Rule& rule, int dimensions) : rule_(rule), dimensions_(dimensions) {
        for (const Stencil& s : ready_stencils(rule.accuracy, dimensions)) stencils_[s.label] = s;
    }

    Program compile(const Formula& formula) {
        scopes_.emplace_back();
        for (const StmtPtr& s : formula.statements) statement(*s, all_cells());
        // The forward Euler step of every chemical; for the other
        // integrators the deltas, which the run combines stage by stage.
        const Value timestep = lookup_value("timestep", {1, 1});
        program_.outputs_are_deltas = rule_.integrator != Integrator::euler;
        for (int i = 0; i < rule_.chemicals; ++i) {
            const std::string chem = chemical_name(i);
            const Value x = lookup_value(chem, {1, 1}), delta = lookup_value("delta_" + chem, {1, 1});
            if (program_.outputs_are_deltas) {
                program_.outputs.push_back(materialise(delta));
                continue;
            }
            Value next = arith(Op::add, x, arith(Op::mul, timestep, delta, {}), {});
            program_.outputs.push_back(materialise(next));
        }
        finish_program(program_);
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
                                         instr.c, instr.truth, instr.mask, static_cast<int>(instr.signs));
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

    // a op b, folded when both are fixed. With Ready's OpenCL arithmetic, a
    // sum or difference with a product of the same expression is one fused
    // multiply-add, as clang contracts it: the left operand's product first.
    Value arith(Op op, Value a, Value b, Pos pos) {
        const bool integer = a.integer && b.integer;
        const bool vector = a.vector || b.vector;
        if (!integer) a = as_real(a), b = as_real(b);
        if (rule_.fused_multiply_add && !integer && (op == Op::add || op == Op::sub)) {
            if (a.product) return fused(*a.product, a.negated, b, op == Op::sub, vector, pos);
            // a - x * y is -(x * y) + a.
            if (b.product) return fused(*b.product, b.negated != (op == Op::sub), a, false, vector, pos);
        }
        a = stored(a), b = stored(b);
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
                same = stored(same);
                same.vector = vector;
                // clang keeps x * 1.0f as a multiplication (the constant is
                // not folded into the other operand): a sum it meets is
                // still one fused multiply-add, x + c rounded once.
                if (rule_.fused_multiply_add && op == Op::mul)
                    same.product = std::make_shared<const Product>(Product{a, b});
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
        Value out = in_register(emit(in), integer || is_comparison(op), vector);
        if (rule_.fused_multiply_add && op == Op::mul && !integer)
            out.product = std::make_shared<const Product>(Product{a, b});
        return out;
    }

    // (-)(p.x * p.y) (-) c, rounded once: Op::fma, folded when all are fixed.
    Value fused(const Product& p, bool negate_product, Value c, bool negate_addend, bool vector, Pos pos) {
        c = stored(as_real(c));
        if (p.x.fixed && p.y.fixed && c.fixed) {
            const double x = negate_product ? -p.x.constant : p.x.constant, z = negate_addend ? -c.constant : c.constant;
            const double folded = rule_.double_precision
                                      ? std::fma(x, p.y.constant, z)
                                      : static_cast<double>(std::fma(static_cast<float>(x),
                                                                     static_cast<float>(p.y.constant),
                                                                     static_cast<float>(z)));
            return constant(folded, false, vector);
        }
        Instr in = instruction(Op::fma);
        in.a = materialise(p.x);
        in.b = materialise(p.y);
        in.c = materialise(c);
        in.signs = static_cast<std::uint8_t>((negate_product ? Instr::negate_product : 0) |
                                             (negate_addend ? Instr::negate_addend : 0));
        in.pos = pos;
        return in_register(emit(in), false, vector);
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

    Value input(int chemical, int dx, int dy, int dz) {
        const auto key = std::make_tuple(chemical, dx, dy, dz);
        auto it = inputs_.find(key);
        if (it != inputs_.end()) return it->second;
        const int reg = new_register();
        program_.inputs.push_back({reg, chemical, dx, dy, dz});
        program_.radius_x = std::max(program_.radius_x, std::abs(dx));
        program_.radius_y = std::max(program_.radius_y, std::abs(dy));
        program_.radius_z = std::max(program_.radius_z, std::abs(dz));
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
                var.elements = {input(i, 0, 0, 0)};
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
                // As Ready: in a double rule 1.1 is 1.10000002 (formula_value).
                return &(predefined_[name] = constant_variable(constant(formula_value(value), false),
                                                                "a parameter of the rule"));
            }
        if (name == "dx") return &(predefined_[name] = constant_variable(constant(1, false), "the grid spacing"));
        if (name == "x_pos" || name == "y_pos" || name == "z_pos") {
            const int reg = new_register();
            (name == "x_pos" ? program_.x_pos : name == "y_pos" ? program_.y_pos : program_.z_pos) = reg;
            return &(predefined_[name] =
                         constant_variable(in_register(reg, false, rule_.block_x == 4), "the cell's position"));
        }
        if (name == "M_PI" || name == "M_PI_F")
            return &(predefined_[name] = constant_variable(constant(3.14159265358979323846, false), "a constant"));
        if (name == "M_E" || name == "M_E_F")
            return &(predefined_[name] = constant_variable(constant(2.71828182845904523536, false), "a constant"));
        // A neighbour: chemical, then u/d, n/s and e/w each with a count
        // (Ready's names: a_n, a_se, a_e2, a_n2w3, a_ud2; on a grid of fewer
        // dimensions the offsets along the missing axes wrap or clamp to
        // the cell itself, as Ready's indexing does).
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
                             constant_variable(input(chem, offset[2], offset[1], offset[0]), "a neighbour's value"));
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
                    // pow(x_gradient, 2) + pow(y_gradient, 2) + ..., one
                    // term a dimension, as Ready writes it.
                    const Value two = constant(2, false);
                    Value sum = call(Fn::pow, {apply_stencil(stencils_.at("x_gradient"), c), two}, {});
                    for (const char* axis : {"y_gradient", "z_gradient"}) {
                        if ((axis[0] == 'y' && dimensions_ < 2) || (axis[0] == 'z' && dimensions_ < 3)) break;
                        const Value g = call(Fn::pow, {apply_stencil(stencils_.at(axis), c), two}, {});
                        sum = arith(Op::add, sum, g, {});
                    }
                    return &(predefined_[name] = constant_variable(sum, "a stencil of the rule's chemicals"));
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
                    const Value v = input(chemical, p.x, p.y, p.z);
                    vector |= v.vector;
                    sum.terms.push_back({1.0, {v.reg}});
                }
                continue;
            }
            StencilSum::Term term{round_real(weight), {}};
            for (const StencilPoint& p : points) {
                const Value v = input(chemical, p.x, p.y, p.z);
                vector |= v.vector;
                term.inputs.push_back(v.reg);
            }
            sum.terms.push_back(std::move(term));
        }
        sum.fused = rule_.fused_multiply_add;
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
            Value negated = in_register(emit(in), v.integer, v.vector);
            // -(x * y) + c is still one fused multiply-add for clang.
            negated.product = v.product;
            negated.negated = !v.negated;
            return negated;
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
                var.elements = {stored(d.init ? converted(expression(*d.init), s.type, d.init->pos) : zero)};
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
        var->elements[index] = stored(value);
    }

    const Rule& rule_;
    int dimensions_ = 2;
    std::map<std::string, Stencil> stencils_;
    std::vector<std::unordered_map<std::string, Variable>> scopes_;
    std::unordered_map<std::string, Variable> predefined_;
    std::map<std::tuple<int, int, int, int>, Value> inputs_;
    std::map<std::pair<double, bool>, int> constant_regs_;
    int division_mask_ = -1;
    std::map<std::tuple<int, int, int, int, int, double, int, int>, int> emitted_;
    int statements_run_ = 0;
    Program program_;
};

}  // namespace

Program compile(const Rule& rule, int dimensions) {
    if (dimensions < 1 || dimensions > 3)
        throw std::invalid_argument("a grid of " + std::to_string(dimensions) + " dimensions: figgen runs 1, 2 or 3");
    return Compiler(rule, dimensions).compile(parse(rule.code));
}

}  // namespace sim::formula
