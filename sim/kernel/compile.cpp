// A kernel's tree compiled into lane programs: OpenCL C's types and
// conversions, vectors as their components, functions inlined, control
// flow as masks (sim/kernel/lanes.hpp).

#include "sim/kernel/compile.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "sim/kernel/ops.hpp"

namespace sim::kernel {

namespace {

using ops::Binary;
using ops::Compare;
using ops::Math1;
using ops::Math2;
using ops::Math3;

[[noreturn]] void fail(int line, const std::string& what) {
    throw KernelError("kernel line " + std::to_string(line) + ": " + what);
}

std::string quoted(const std::string& s) { return "\"" + s.substr(0, 40) + (s.size() > 40 ? "...\"" : "\""); }

// C's ranks: which of two scalar types an operation of both is done in.
Scalar promoted(Scalar s) { return s == Scalar::b ? Scalar::i32 : s; }
Scalar common_scalar(Scalar a, Scalar b) {
    a = promoted(a), b = promoted(b);
    if (a == Scalar::f64 || b == Scalar::f64) return Scalar::f64;
    if (a == Scalar::f32 || b == Scalar::f32) return Scalar::f32;
    if (a == b) return a;
    auto rank = [](Scalar s) { return s == Scalar::i32 || s == Scalar::u32 ? 1 : 2; };
    if (is_signed(a) == is_signed(b)) return rank(a) >= rank(b) ? a : b;
    const Scalar u = is_signed(a) ? b : a, s = is_signed(a) ? a : b;
    if (rank(u) >= rank(s)) return u;
    return s;  // long and uint: long holds every uint
}
// The integer type a comparison of vectors of `s` gives, -1 or 0 each.
Scalar mask_scalar(Scalar s) { return bytes_of(s) == 8 ? Scalar::i64 : Scalar::i32; }

struct Value {
    Type type{Scalar::i32, 0};
    std::vector<int> regs;  // one a component
    // A float product just computed, a * b, each component's a and b:
    // added or subtracted in the same expression, it becomes one fused
    // multiply-add, as OpenCL C's FP_CONTRACT ON lets pocl's clang make it
    // (a * b + c, c + a * b, a * b - c, c - a * b); stored first, it stays two roundings.
    std::vector<std::pair<int, int>> factors;
};

struct Symbol {
    enum class Kind { var, array, buffer } kind = Kind::var;
    Type type;
    std::vector<int> regs;  // var
    int array = -1;         // array: Compiled::arrays
    int view = -1;          // buffer: Compiled::buffers
    bool is_const = false;
    bool owner = false;     // an array declared here, not a parameter that names one
};

// What a name assigned or indexed is: a variable's components, an array's
// element, a buffer's element; `comps` picks components of the element.
struct Place {
    enum class Kind { var, array, buffer } kind = Kind::var;
    Type type;              // of the place (after a swizzle)
    std::vector<int> regs;  // var
    int array = -1, view = -1;
    int index = -1;         // array, buffer: an i64 register
    std::vector<int> comps;
    bool is_const = false;
    std::string name;
};

struct Frame {
    Type result{Scalar::i32, 0};
    std::vector<int> result_regs;
    int returned = 0;
    int returns = 0;  // return statements compiled in its body
};

struct Target {
    int broken = 0, continued = -1;  // continued -1: a switch
};

class Compiler {
public:
    Compiler(const Program& program, const Interface& iface) : prog_(program), iface_(iface) {}

    Compiled run() {
        c_.global[0] = iface_.global[0];
        c_.global[1] = iface_.global[1];
        c_.global[2] = iface_.global[2];
        c_.trip_budget = iface_.trip_budget;
        c_.masks = 2;
        for (int k = 0; k < 3; ++k) c_.id_registers[k] = alloc();
        c_.blocks.resize(2);
        scopes_.emplace_back();
        for (const Function& f : prog_.functions) {
            if (f.body) {
                if (functions_.count(f.name)) fail(f.line, "the function " + quoted(f.name) + " is defined twice");
                functions_[f.name] = &f;
            }
        }
        // program-scope constants
        block_ = 0;
        for (const Declaration& d : prog_.constants) {
            temps_.emplace_back();
            declare(d);
            release_temps();
        }
        const auto k = functions_.find(iface_.entry);
        if (k == functions_.end() || !k->second->is_kernel)
            throw KernelError("the kernel has no __kernel function " + quoted(iface_.entry));
        kernel(*k->second);
        for (const Block& b : c_.blocks) c_.operations += static_cast<int>(b.ops.size());
        return std::move(c_);
    }

private:
    // registers
    int alloc() {
        int r;
        if (!free_.empty()) {
            r = *free_.begin();
            free_.erase(free_.begin());
        } else {
            r = c_.registers++;
            if (c_.registers > max_registers)
                fail(line_, "the kernel needs more than " + std::to_string(max_registers) +
                                " registers a work item (its variables, arrays and inlined calls)");
        }
        return r;
    }
    int temp() {
        const int r = alloc();
        temps_.back().push_back(r);
        return r;
    }
    void release_temps() {
        for (int r : temps_.back()) free_.insert(r);
        temps_.pop_back();
    }
    int mask() {
        if (c_.masks >= max_masks) fail(line_, "the kernel's control flow needs more than " + std::to_string(max_masks) + " masks");
        return c_.masks++;
    }
    int new_block() {
        c_.blocks.emplace_back();
        return static_cast<int>(c_.blocks.size()) - 1;
    }
    void emit(Op op) {
        op.line = line_;
        if (++operations_ > max_operations)
            fail(line_, "the kernel, its calls inlined, is more than " + std::to_string(max_operations) + " operations");
        c_.blocks[static_cast<std::size_t>(block_)].ops.push_back(op);
    }
    void emit(OpFn fn, int dst, int a = -1, int b = -1, int cc = -1) {
        Op op;
        op.fn = fn;
        op.dst = dst, op.a = a, op.b = b, op.c = cc;
        emit(op);
    }

    // values
    Value constant_value(Scalar s, std::int64_t i, double f) {
        Op op;
        op.fn = ops::constant(s);
        op.dst = temp();
        op.i = i;
        op.f = f;
        emit(op);
        return Value{Type{s, 1}, {op.dst}};
    }
    Value int_value(std::int64_t v) { return constant_value(Scalar::i32, v, 0); }

    Value convert(const Value& v, const Type& to) {
        if (v.type == to) return v;
        if (to.is_void()) return Value{};
        if (v.type.is_void()) fail(line_, "a void value where a " + type_name(to) + " is wanted");
        if (v.type.is_vector() && v.type.width != to.width)
            fail(line_, "a " + type_name(v.type) + " where a " + type_name(to) + " is wanted");
        if (v.type.is_vector() && v.type.scalar != to.scalar)
            fail(line_, "a " + type_name(v.type) + " where a " + type_name(to) +
                            " is wanted: OpenCL C converts vectors with convert_" + type_name(to));
        Value out{to, {}};
        int scalar_reg = -1;
        for (int k = 0; k < to.width; ++k) {
            const int src = v.regs[static_cast<std::size_t>(v.type.is_vector() ? k : 0)];
            if (!v.type.is_vector() && scalar_reg >= 0) {
                out.regs.push_back(scalar_reg);
                continue;
            }
            int dst = src;
            if (v.type.scalar != to.scalar) {
                dst = temp();
                emit(ops::convert(v.type.scalar, to.scalar), dst, src);
            }
            if (!v.type.is_vector()) scalar_reg = dst;
            out.regs.push_back(dst);
        }
        return out;
    }

    // A scalar as a mask: for if, loops, && and ||.
    int condition(const Expr& e) {
        Value v = expr(e);
        return to_mask(v);
    }
    int to_mask(const Value& v) {
        if (v.type.is_void() || v.type.is_vector())
            fail(line_, "a " + type_name(v.type) + " where a condition (a scalar) is wanted");
        const int m = mask();
        emit(ops::to_mask(v.type.scalar), m, v.regs[0]);
        return m;
    }

    // names
    Symbol* find(const std::string& name) {
        for (auto s = scopes_.rbegin(); s != scopes_.rend(); ++s) {
            const auto i = s->find(name);
            if (i != s->end()) return &i->second;
        }
        return nullptr;
    }
    void bind(const std::string& name, Symbol s) {
        if (scopes_.back().count(name)) fail(line_, quoted(name) + " is declared twice in one scope");
        scopes_.back()[name] = std::move(s);
    }
    void pop_scope() {
        for (auto& [name, s] : scopes_.back()) {
            if (s.kind == Symbol::Kind::var && owned_.count(s.regs.empty() ? -1 : s.regs[0]))
                for (int r : s.regs) free_.insert(r), owned_.erase(r);
            if (s.kind == Symbol::Kind::array && s.owner && owned_arrays_.count(s.array)) {
                const ArrayInfo& a = c_.arrays[static_cast<std::size_t>(s.array)];
                for (long long i = 0; i < a.count * a.width; ++i) free_.insert(a.base + static_cast<int>(i));
                owned_arrays_.erase(s.array);
            }
        }
        scopes_.pop_back();
    }
    std::vector<int> variable(const Type& t) {
        std::vector<int> regs;
        for (int k = 0; k < t.width; ++k) {
            regs.push_back(alloc());
            owned_.insert(regs.back());
        }
        return regs;
    }

    // Constants OpenCL C defines as macros.
    std::optional<Value> named_constant(const std::string& n) {
        static const std::map<std::string, std::pair<Scalar, double>> reals = {
            {"M_PI", {Scalar::f64, 3.14159265358979323846}},      {"M_PI_F", {Scalar::f32, 3.14159265358979323846}},
            {"M_PI_2", {Scalar::f64, 1.57079632679489661923}},    {"M_PI_2_F", {Scalar::f32, 1.57079632679489661923}},
            {"M_PI_4", {Scalar::f64, 0.78539816339744830962}},    {"M_PI_4_F", {Scalar::f32, 0.78539816339744830962}},
            {"M_1_PI", {Scalar::f64, 0.31830988618379067154}},    {"M_1_PI_F", {Scalar::f32, 0.31830988618379067154}},
            {"M_2_PI", {Scalar::f64, 0.63661977236758134308}},    {"M_2_PI_F", {Scalar::f32, 0.63661977236758134308}},
            {"M_E", {Scalar::f64, 2.71828182845904523536}},       {"M_E_F", {Scalar::f32, 2.71828182845904523536}},
            {"M_SQRT2", {Scalar::f64, 1.41421356237309504880}},   {"M_SQRT2_F", {Scalar::f32, 1.41421356237309504880}},
            {"M_SQRT1_2", {Scalar::f64, 0.70710678118654752440}}, {"M_SQRT1_2_F", {Scalar::f32, 0.70710678118654752440}},
            {"M_LN2", {Scalar::f64, 0.69314718055994530942}},     {"M_LN2_F", {Scalar::f32, 0.69314718055994530942}},
            {"M_LN10", {Scalar::f64, 2.30258509299404568402}},    {"M_LN10_F", {Scalar::f32, 2.30258509299404568402}},
            {"MAXFLOAT", {Scalar::f32, 3.40282346638528859812e+38}}, {"FLT_MAX", {Scalar::f32, 3.40282346638528859812e+38}},
            {"FLT_MIN", {Scalar::f32, 1.17549435082228750797e-38}}, {"FLT_EPSILON", {Scalar::f32, 1.1920928955078125e-7}},
            {"DBL_MAX", {Scalar::f64, std::numeric_limits<double>::max()}},
            {"DBL_MIN", {Scalar::f64, std::numeric_limits<double>::min()}},
            {"DBL_EPSILON", {Scalar::f64, std::numeric_limits<double>::epsilon()}},
            {"INFINITY", {Scalar::f32, std::numeric_limits<double>::infinity()}},
            {"HUGE_VALF", {Scalar::f32, std::numeric_limits<double>::infinity()}},
            {"HUGE_VAL", {Scalar::f64, std::numeric_limits<double>::infinity()}},
            {"NAN", {Scalar::f32, std::numeric_limits<double>::quiet_NaN()}},
        };
        const auto r = reals.find(n);
        if (r != reals.end()) {
            const double v = r->second.first == Scalar::f32 ? static_cast<double>(static_cast<float>(r->second.second)) : r->second.second;
            return constant_value(r->second.first, 0, v);
        }
        if (n == "INT_MAX") return constant_value(Scalar::i32, std::numeric_limits<std::int32_t>::max(), 0);
        if (n == "INT_MIN") return constant_value(Scalar::i32, std::numeric_limits<std::int32_t>::min(), 0);
        if (n == "UINT_MAX") return constant_value(Scalar::u32, std::numeric_limits<std::uint32_t>::max(), 0);
        if (n == "true") return int_value(1);
        if (n == "false") return int_value(0);
        return std::nullopt;
    }

    // expressions
    Value expr(const Expr& e) {
        line_ = e.line;
        switch (e.kind) {
        case Expr::Kind::integer: return constant_value(e.type.scalar, static_cast<std::int64_t>(e.integer), 0);
        case Expr::Kind::real: return constant_value(e.type.scalar, 0, e.real);
        case Expr::Kind::name: {
            Symbol* s = find(e.text);
            if (!s) {
                if (auto v = named_constant(e.text)) return *v;
                fail(e.line, quoted(e.text) + " is not declared");
            }
            if (s->kind != Symbol::Kind::var)
                fail(e.line, quoted(e.text) + " is " + (s->kind == Symbol::Kind::buffer ? "a buffer" : "an array") +
                                 ": index it");
            return Value{s->type, s->regs};
        }
        case Expr::Kind::index: return load(place(e));
        case Expr::Kind::member: {
            const Expr::Kind base = e.args[0]->kind;
            if (base == Expr::Kind::name || base == Expr::Kind::index || base == Expr::Kind::member) return load(place(e));
            Value v = expr(*e.args[0]);  // a swizzle of a value computed here
            line_ = e.line;
            if (v.type.is_void()) fail(e.line, "." + e.text + " of a void value");
            Value out{Type{v.type.scalar, 0}, {}};
            for (int k : swizzle(e.text, v.type)) out.regs.push_back(v.regs[static_cast<std::size_t>(k)]);
            out.type.width = static_cast<int>(out.regs.size());
            return out;
        }
        case Expr::Kind::call: return call(e);
        case Expr::Kind::cast: {
            Value v = expr(*e.args[0]);
            line_ = e.line;
            if (e.type.is_void()) return Value{};
            if (e.type.is_vector() && v.type.is_vector() && !(v.type == e.type))
                fail(e.line, "a cast of a " + type_name(v.type) + " to a " + type_name(e.type) +
                                 ": OpenCL C converts vectors with convert_" + type_name(e.type));
            if (!e.type.is_vector() && v.type.is_vector())
                fail(e.line, "a cast of a " + type_name(v.type) + " to a scalar");
            return convert(v, e.type);
        }
        case Expr::Kind::vector: return vector_literal(e);
        case Expr::Kind::unary: return unary(e);
        case Expr::Kind::postfix: {
            Place p = place(*e.args[0]);
            line_ = e.line;
            Value old = load(p);
            Value kept = copy_to_temps(old);
            Value one = convert(int_value(1), Type{p.type.scalar, 1});
            store(p, arithmetic(e.text == "++" ? "+" : "-", old, one));
            return kept;
        }
        case Expr::Kind::binary: return binary(e);
        case Expr::Kind::assign: return assignment(e);
        case Expr::Kind::ternary: return ternary(e);
        case Expr::Kind::comma:
            expr(*e.args[0]);
            return expr(*e.args[1]);
        case Expr::Kind::list: fail(e.line, "a { } list outside an initialiser");
        }
        fail(e.line, "an expression figgen does not read");
    }

    Value copy_to_temps(const Value& v) {
        Value out{v.type, {}};
        for (int r : v.regs) {
            const int t = temp();
            emit(ops::copy(v.type.scalar), t, r);
            out.regs.push_back(t);
        }
        return out;
    }

    Value vector_literal(const Expr& e) {
        std::vector<int> regs;
        for (const ExprPtr& a : e.args) {
            Value v = expr(*a);
            line_ = e.line;
            if (v.type.is_void()) fail(e.line, "a void value in a vector literal");
            Value c = convert(v, Type{e.type.scalar, v.type.width});
            for (int r : c.regs) regs.push_back(r);
        }
        if (regs.size() == 1) regs.assign(static_cast<std::size_t>(e.type.width), regs[0]);
        if (static_cast<int>(regs.size()) != e.type.width)
            fail(e.line, "a " + type_name(e.type) + " literal of " + std::to_string(regs.size()) + " values");
        return Value{e.type, regs};
    }

    Value unary(const Expr& e) {
        if (e.text == "++" || e.text == "--") {
            Place p = place(*e.args[0]);
            line_ = e.line;
            Value one = convert(int_value(1), Type{p.type.scalar, 1});
            Value v = arithmetic(e.text == "++" ? "+" : "-", load(p), one);
            Value r = convert(v, p.type);
            store(p, r);
            return r;
        }
        Value v = expr(*e.args[0]);
        line_ = e.line;
        if (v.type.is_void()) fail(e.line, "a void value after " + e.text);
        if (e.text == "+") return convert(v, Type{promoted(v.type.scalar), v.type.width});
        if (e.text == "-") {
            Value p = convert(v, Type{promoted(v.type.scalar), v.type.width});
            return map(p, p.type, [&](int r) { return one_op(ops::unary(ops::Unary::neg, p.type.scalar, p.type.scalar), r); });
        }
        if (e.text == "~") {
            if (is_float(v.type.scalar)) fail(e.line, "~ of a " + type_name(v.type));
            Value p = convert(v, Type{promoted(v.type.scalar), v.type.width});
            return map(p, p.type, [&](int r) { return one_op(ops::unary(ops::Unary::bit_not, p.type.scalar, p.type.scalar), r); });
        }
        // !
        if (v.type.is_vector()) {
            const Type rt{mask_scalar(v.type.scalar), v.type.width};
            return map(v, rt, [&](int r) { return one_op(ops::unary(ops::Unary::vec_not, v.type.scalar, rt.scalar), r); });
        }
        return map(v, Type{Scalar::i32, 1}, [&](int r) { return one_op(ops::unary(ops::Unary::log_not, v.type.scalar, Scalar::i32), r); });
    }

    int one_op(OpFn fn, int a, int b = -1, int cc = -1) {
        if (!fn) fail(line_, "an operation on a type it does not take");
        const int d = temp();
        emit(fn, d, a, b, cc);
        return d;
    }
    template <class F>
    Value map(const Value& v, const Type& result, F f) {
        Value out{result, {}};
        for (int r : v.regs) out.regs.push_back(f(r));
        return out;
    }

    // The type two operands are brought to.
    Type common(const Type& a, const Type& b) {
        if (a.is_void() || b.is_void()) fail(line_, "a void value in an expression");
        if (a.is_vector() && b.is_vector()) {
            if (!(a == b)) fail(line_, "an operation on a " + type_name(a) + " and a " + type_name(b));
            return a;
        }
        if (a.is_vector()) return a;
        if (b.is_vector()) return b;
        return Type{common_scalar(a.scalar, b.scalar), 1};
    }

    Value arithmetic(const std::string& op, const Value& x, const Value& y) {
        static const std::map<std::string, Binary> binaries = {
            {"+", Binary::add},     {"-", Binary::sub},    {"*", Binary::mul},     {"/", Binary::div},
            {"%", Binary::rem},     {"&", Binary::bit_and}, {"|", Binary::bit_or}, {"^", Binary::bit_xor},
            {"<<", Binary::shl},    {">>", Binary::shr}};
        const Binary b = binaries.at(op);
        Type t;
        if (b == Binary::shl || b == Binary::shr) {
            if (x.type.is_void() || y.type.is_void()) fail(line_, "a void value in an expression");
            t = Type{promoted(x.type.scalar), x.type.width};
            if (y.type.is_vector() && !x.type.is_vector()) fail(line_, "a scalar shifted by a vector");
        } else {
            t = common(x.type, y.type);
        }
        if (is_float(t.scalar) && b != Binary::add && b != Binary::sub && b != Binary::mul && b != Binary::div)
            fail(line_, quoted(op) + " on a " + type_name(t) + ": OpenCL C takes it on integers alone");
        Value a = convert(x, t), c = convert(y, Type{t.scalar, y.type.width == 1 ? 1 : t.width});
        c = convert(c, t);
        Value out{t, {}};
        const bool contract = is_float(t.scalar) && (b == Binary::add || b == Binary::sub);
        for (int k = 0; k < t.width; ++k) {
            const auto K = static_cast<std::size_t>(k);
            if (contract && (!a.factors.empty() || !c.factors.empty())) {
                // (a0 * a1) + c = fma(a0, a1, c); (a0 * a1) - c = fma(a0, a1, -c);
                // a + (c0 * c1) = fma(c0, c1, a); a - (c0 * c1) = fma(-c0, c1, a)
                const OpFn neg = ops::unary(ops::Unary::neg, t.scalar, t.scalar);
                int p, q, r;
                if (!a.factors.empty()) {
                    p = a.factors[K].first, q = a.factors[K].second;
                    r = b == Binary::sub ? one_op(neg, c.regs[K]) : c.regs[K];
                } else {
                    p = b == Binary::sub ? one_op(neg, c.factors[K].first) : c.factors[K].first;
                    q = c.factors[K].second;
                    r = a.regs[K];
                }
                out.regs.push_back(one_op(ops::math3(Math3::fma, t.scalar), p, q, r));
                continue;
            }
            out.regs.push_back(one_op(ops::binary(b, t.scalar), a.regs[K], c.regs[K]));
            if (is_float(t.scalar) && b == Binary::mul) out.factors.emplace_back(a.regs[K], c.regs[K]);
        }
        return out;
    }

    Value binary(const Expr& e) {
        const std::string& op = e.text;
        if (op == "&&" || op == "||") return logical(e);
        Value x = expr(*e.args[0]);
        Value y = expr(*e.args[1]);
        line_ = e.line;
        static const std::map<std::string, Compare> compares = {{"==", Compare::eq}, {"!=", Compare::ne},
                                                                {"<", Compare::lt},  {">", Compare::gt},
                                                                {"<=", Compare::le}, {">=", Compare::ge}};
        const auto k = compares.find(op);
        if (k != compares.end()) {
            const Type t = common(x.type, y.type);
            Value a = convert(x, t), b = convert(y, t);
            const Type rt = t.is_vector() ? Type{mask_scalar(t.scalar), t.width} : Type{Scalar::i32, 1};
            Value out{rt, {}};
            for (int c = 0; c < t.width; ++c)
                out.regs.push_back(one_op(ops::compare(k->second, t.scalar, rt.scalar, t.is_vector()),
                                          a.regs[static_cast<std::size_t>(c)], b.regs[static_cast<std::size_t>(c)]));
            return out;
        }
        return arithmetic(op, x, y);
    }

    // && and ||: the right side runs only in the lanes that need it.
    Value logical(const Expr& e) {
        const int left = condition(*e.args[0]);
        line_ = e.line;
        const bool is_and = e.text == "&&";
        GuardNode g;
        g.cond = left;
        g.saved = mask();
        g.first_mask = mask();
        g.second_mask = mask();
        g.first = g.second = -1;
        const int outer = block_;
        const int sub = new_block();
        block_ = sub;
        const int right = condition(*e.args[1]);
        block_ = outer;
        line_ = e.line;
        (is_and ? g.first : g.second) = sub;
        c_.guards.push_back(g);
        Op op;
        op.fn = ops::guard_node();
        op.aux = static_cast<int>(c_.guards.size()) - 1;
        emit(op);
        const int m = mask();
        if (is_and) emit(ops::mask_and(), m, left, right);
        else {
            // where left is true the right side did not run: its lanes hold what they held
            const int r = mask();
            emit(ops::mask_and(), r, g.second_mask, right);
            emit(ops::mask_or(), m, left, r);
        }
        const int d = temp();
        emit(ops::from_mask(), d, m);
        return Value{Type{Scalar::i32, 1}, {d}};
    }

    Value ternary(const Expr& e) {
        const int cond = condition(*e.args[0]);
        line_ = e.line;
        GuardNode g;
        g.cond = cond;
        g.saved = mask();
        g.first_mask = mask();
        g.second_mask = mask();
        const int outer = block_;
        g.first = new_block();
        block_ = g.first;
        Value x = expr(*e.args[1]);
        g.second = new_block();
        block_ = g.second;
        Value y = expr(*e.args[2]);
        line_ = e.line;
        if (x.type.is_void() != y.type.is_void()) fail(e.line, "one side of ?: is void and the other is not");
        Type t = x.type.is_void() ? x.type : common(x.type, y.type);
        block_ = g.first;
        x = convert(x, t);
        block_ = g.second;
        y = convert(y, t);
        block_ = outer;
        c_.guards.push_back(g);
        Op op;
        op.fn = ops::guard_node();
        op.aux = static_cast<int>(c_.guards.size()) - 1;
        emit(op);
        if (t.is_void()) return Value{};
        Value out{t, {}};
        for (int k = 0; k < t.width; ++k)
            out.regs.push_back(one_op(ops::select(t.scalar), y.regs[static_cast<std::size_t>(k)], x.regs[static_cast<std::size_t>(k)], cond));
        return out;
    }

    Value assignment(const Expr& e) {
        Place p = place(*e.args[0]);
        if (p.is_const) fail(e.line, "assigns " + quoted(p.name) + ", which is const");
        Value v;
        if (e.text == "=") {
            v = expr(*e.args[1]);
            line_ = e.line;
        } else {
            Value old = load(p);
            Value y = expr(*e.args[1]);
            line_ = e.line;
            v = arithmetic(e.text.substr(0, e.text.size() - 1), old, y);
        }
        if (v.type.is_vector() && !p.type.is_vector())
            fail(e.line, "assigns a " + type_name(v.type) + " to a " + type_name(p.type));
        Value r = convert(v, p.type);
        store(p, r);
        return r;
    }

    // The place an expression names: a variable, a swizzle of one, an
    // element of an array or a buffer.
    Place place(const Expr& e) {
        line_ = e.line;
        if (e.kind == Expr::Kind::name) {
            Symbol* s = find(e.text);
            if (!s) fail(e.line, quoted(e.text) + " is not declared");
            if (s->kind != Symbol::Kind::var) fail(e.line, quoted(e.text) + " is an array or buffer: index it");
            Place p;
            p.kind = Place::Kind::var;
            p.type = s->type;
            p.regs = s->regs;
            p.is_const = s->is_const;
            p.name = e.text;
            return p;
        }
        if (e.kind == Expr::Kind::member) {
            Place p = place(*e.args[0]);
            line_ = e.line;
            const std::vector<int> picked = swizzle(e.text, p.type);
            std::vector<int> comps;
            for (int k : picked) comps.push_back(p.kind == Place::Kind::var ? p.regs[static_cast<std::size_t>(k)] : p.comps[static_cast<std::size_t>(k)]);
            if (p.kind == Place::Kind::var) p.regs = comps;
            else p.comps = comps;
            p.type = Type{p.type.scalar, static_cast<int>(picked.size())};
            return p;
        }
        if (e.kind == Expr::Kind::index) {
            // a[i][j]...: down to the name
            std::vector<const Expr*> indices;
            const Expr* base = &e;
            while (base->kind == Expr::Kind::index) {
                indices.insert(indices.begin(), base->args[1].get());
                base = base->args[0].get();
            }
            if (base->kind != Expr::Kind::name) fail(e.line, "only a buffer or an array is indexed");
            Symbol* s = find(base->text);
            if (!s) fail(e.line, quoted(base->text) + " is not declared");
            Place p;
            p.name = base->text;
            p.is_const = s->is_const;
            if (s->kind == Symbol::Kind::buffer) {
                if (indices.size() != 1) fail(e.line, "the buffer " + quoted(base->text) + " takes one index");
                p.kind = Place::Kind::buffer;
                p.view = s->view;
                p.type = s->type;
                p.index = index_register(*indices[0]);
            } else if (s->kind == Symbol::Kind::array) {
                const ArrayInfo& a = c_.arrays[static_cast<std::size_t>(s->array)];
                if (indices.size() != a.dims.size())
                    fail(e.line, "the array " + quoted(base->text) + " takes " + std::to_string(a.dims.size()) +
                                     " indices, not " + std::to_string(indices.size()));
                p.kind = Place::Kind::array;
                p.array = s->array;
                p.type = s->type;
                int flat = -1;
                for (std::size_t k = 0; k < indices.size(); ++k) {
                    const int i = index_register(*indices[k]);
                    line_ = e.line;
                    Op check;
                    check.fn = ops::check_index();
                    check.a = i;
                    check.i = a.dims[k];
                    check.aux = s->array;
                    emit(check);
                    if (flat < 0) flat = i;
                    else {
                        Value dim = constant_value(Scalar::i64, a.dims[k], 0);
                        const int scaled = one_op(ops::binary(Binary::mul, Scalar::i64), flat, dim.regs[0]);
                        flat = one_op(ops::binary(Binary::add, Scalar::i64), scaled, i);
                    }
                }
                p.index = flat;
            } else {
                fail(e.line, quoted(base->text) + " is a variable, not a buffer or an array");
            }
            for (int k = 0; k < p.type.width; ++k) p.comps.push_back(k);
            return p;
        }
        fail(e.line, "this expression is not a place a value can be stored");
    }

    int index_register(const Expr& e) {
        Value v = expr(e);
        line_ = e.line;
        if (v.type.is_void() || v.type.is_vector() || is_float(v.type.scalar))
            fail(e.line, "an index is a " + type_name(v.type) + ": OpenCL C indexes with integers");
        return convert(v, Type{Scalar::i64, 1}).regs[0];
    }

    std::vector<int> swizzle(const std::string& s, const Type& t) {
        if (!t.is_vector()) fail(line_, "." + s + " of a " + type_name(t) + ", which is not a vector");
        std::vector<int> out;
        auto in_range = [&](int k) {
            if (k >= t.width) fail(line_, "." + s + " of a " + type_name(t) + " reaches past its " + std::to_string(t.width) + " components");
            out.push_back(k);
        };
        if (s == "lo" || s == "hi" || s == "even" || s == "odd") {
            const int half = (t.width + 1) / 2;
            for (int k = 0; k < half; ++k) {
                const int i = s == "lo" ? k : s == "hi" ? half + k : s == "even" ? 2 * k : 2 * k + 1;
                if (i < t.width) out.push_back(i);
                else out.push_back(t.width - 1);
            }
            return out;
        }
        if (s.size() >= 2 && (s[0] == 's' || s[0] == 'S')) {
            for (std::size_t i = 1; i < s.size(); ++i) {
                const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(s[i])));
                if (c >= '0' && c <= '9') in_range(c - '0');
                else if (c >= 'a' && c <= 'f') in_range(10 + c - 'a');
                else fail(line_, "." + s + " is not a vector's components");
            }
        } else {
            for (char c : s) {
                const std::size_t k = std::string("xyzw").find(c);
                if (k == std::string::npos) fail(line_, "." + s + " is not a vector's components");
                in_range(static_cast<int>(k));
            }
        }
        if (out.size() > 4) fail(line_, "." + s + " picks more than 4 components");
        return out;
    }

    Value load(const Place& p) {
        if (p.kind == Place::Kind::var) return Value{p.type, p.regs};
        Value out{p.type, {}};
        bool checked = false;  // the element's index, by the component before (in the same mask)
        for (int k : p.comps) {
            Op op;
            op.dst = temp();
            op.a = p.index;
            op.i = k;
            if (p.kind == Place::Kind::buffer) {
                op.fn = ops::buffer_load(p.type.scalar);
                op.aux = p.view;
                op.c = checked ? 1 : 0;
                checked = true;
            } else {
                op.fn = ops::array_load(p.type.scalar);
                op.aux = p.array;
            }
            emit(op);
            out.regs.push_back(op.dst);
        }
        return out;
    }

    void store(const Place& p, const Value& v) {
        if (p.is_const) fail(line_, "assigns " + quoted(p.name) + ", which is const");
        if (p.kind == Place::Kind::buffer && !c_.buffers[static_cast<std::size_t>(p.view)].output)
            fail(line_, "writes " + quoted(p.name) + ", a buffer the kernel reads: it writes its outputs alone");
        std::set<int> seen;
        for (std::size_t k = 0; k < p.comps.size() || k < p.regs.size(); ++k) {
            const int where = p.kind == Place::Kind::var ? p.regs[k] : p.comps[k];
            if (!seen.insert(where).second) fail(line_, "assigns one component twice");
            Op op;
            op.a = v.regs[k];
            if (p.kind == Place::Kind::var) {
                op.fn = ops::assign(p.type.scalar);
                op.dst = where;
            } else {
                op.fn = p.kind == Place::Kind::buffer ? ops::buffer_store(p.type.scalar) : ops::array_store(p.type.scalar);
                op.aux = p.kind == Place::Kind::buffer ? p.view : p.array;
                op.a = p.index;
                op.b = v.regs[k];
                op.i = where;
            }
            emit(op);
        }
    }

    // calls
    long long constant_integer(const Expr& e) {
        if (e.kind == Expr::Kind::integer) return static_cast<long long>(e.integer);
        if (e.kind == Expr::Kind::unary && e.text == "-") return -constant_integer(*e.args[0]);
        if (e.kind == Expr::Kind::unary && e.text == "+") return constant_integer(*e.args[0]);
        if (e.kind == Expr::Kind::cast && !is_float(e.type.scalar)) return constant_integer(*e.args[0]);
        if (e.kind == Expr::Kind::binary) {
            const long long a = constant_integer(*e.args[0]), b = constant_integer(*e.args[1]);
            const auto ua = static_cast<unsigned long long>(a), ub = static_cast<unsigned long long>(b);
            if (e.text == "+") return static_cast<long long>(ua + ub);
            if (e.text == "-") return static_cast<long long>(ua - ub);
            if (e.text == "*") return static_cast<long long>(ua * ub);
            if (e.text == "/" && b != 0 && !(a == std::numeric_limits<long long>::min() && b == -1)) return a / b;
            if (e.text == "%" && b != 0 && !(a == std::numeric_limits<long long>::min() && b == -1)) return a % b;
            if (e.text == "<<") return static_cast<long long>(ua << (ub & 63));
            if (e.text == ">>") return a >> (ub & 63);
            if (e.text == "&") return a & b;
            if (e.text == "|") return a | b;
        }
        fail(e.line, "a constant integer is wanted here");
    }

    Value call(const Expr& e) {
        const auto f = functions_.find(e.text);
        if (f != functions_.end()) return inline_call(*f->second, e);
        return builtin(e);
    }

    Value inline_call(const Function& f, const Expr& e) {
        if (f.is_kernel) fail(e.line, "calls the kernel " + quoted(f.name));
        if (std::find(calls_.begin(), calls_.end(), f.name) != calls_.end())
            fail(e.line, quoted(f.name) + " calls itself: OpenCL C has no recursion");
        if (calls_.size() >= 64) fail(e.line, "calls nest more than 64 deep");
        if (e.args.size() != f.parameters.size())
            fail(e.line, quoted(f.name) + " takes " + std::to_string(f.parameters.size()) + " arguments, not " +
                             std::to_string(e.args.size()));
        std::map<std::string, Symbol> params;
        for (std::size_t k = 0; k < f.parameters.size(); ++k) {
            const Declaration& d = f.parameters[k].declaration;
            const std::string& name = d.names[0].name;
            const Expr& arg = *e.args[k];
            if (d.pointer) {
                if (arg.kind != Expr::Kind::name) fail(arg.line, "the pointer argument " + quoted(name) + " of " + quoted(f.name) + " is not a buffer's or an array's name");
                Symbol* s = find(arg.text);
                if (!s || s->kind == Symbol::Kind::var)
                    fail(arg.line, "the pointer argument " + quoted(name) + " of " + quoted(f.name) + " is not a buffer or an array");
                if (!(s->type == d.type))
                    fail(arg.line, "passes " + quoted(arg.text) + " (of " + type_name(s->type) + ") as " + quoted(name) + " (of " + type_name(d.type) + ")");
                Symbol alias = *s;
                alias.owner = false;
                alias.is_const = alias.is_const || d.is_const;
                params[name] = alias;
                continue;
            }
            Value v = expr(arg);
            line_ = arg.line;
            if (v.type.is_vector() && !d.type.is_vector())
                fail(arg.line, "passes a " + type_name(v.type) + " as " + quoted(name) + ", a " + type_name(d.type));
            Value c = convert(v, d.type);
            Symbol s;
            s.type = d.type;
            s.is_const = d.is_const;
            // the parameter is the caller's temporary: it lives while the call's statement does
            for (int r : c.regs) {
                const int t = temp();
                emit(ops::copy(d.type.scalar), t, r);
                s.regs.push_back(t);
            }
            params[name] = s;
        }
        line_ = e.line;
        Frame frame;
        frame.result = f.result;
        for (int k = 0; k < f.result.width; ++k) {
            frame.result_regs.push_back(temp());
            Op zero;
            zero.fn = ops::constant(f.result.scalar);
            zero.dst = frame.result_regs.back();
            emit(zero);
        }
        frame.returned = mask();
        CallNode node;
        node.returned = frame.returned;
        node.join = mask();
        node.body = new_block();
        const int outer = block_;
        block_ = node.body;
        calls_.push_back(f.name);
        frames_.push_back(frame);
        const auto saved_targets = std::move(targets_);
        targets_.clear();
        // the function sees program-scope names and its parameters alone
        auto saved_scopes = std::move(scopes_);
        scopes_.clear();
        scopes_.push_back(saved_scopes.front());
        scopes_.push_back(std::move(params));
        for (const StmtPtr& s : f.body->body) statement(*s);
        pop_scope();
        scopes_ = std::move(saved_scopes);
        targets_ = saved_targets;
        const int returns = frames_.back().returns;
        frames_.pop_back();
        calls_.pop_back();
        block_ = outer;
        line_ = e.line;
        // A body whose one return is its last statement (or that has none)
        // ends with every lane it began with: it runs in line, in the
        // caller's block and mask, without a call's masks.
        std::vector<Op>& body = c_.blocks[static_cast<std::size_t>(node.body)].ops;
        const bool last_returns = !body.empty() && body.back().fn == ops::jump() && body.back().aux == frame.returned;
        if (returns == 0 || (returns == 1 && last_returns)) {
            if (returns == 1) body.pop_back();
            std::vector<Op>& here = c_.blocks[static_cast<std::size_t>(block_)].ops;
            here.insert(here.end(), body.begin(), body.end());
            body.clear();
            return Value{f.result, frame.result_regs};
        }
        c_.calls.push_back(node);
        Op op;
        op.fn = ops::call_node();
        op.aux = static_cast<int>(c_.calls.size()) - 1;
        emit(op);
        return Value{f.result, frame.result_regs};
    }

    // The widest of the arguments' types, in floats when `floats`.
    Type widest(const std::vector<Value>& args, bool floats) {
        Type t{Scalar::i32, 1};
        bool first = true;
        for (const Value& a : args) {
            if (a.type.is_void()) fail(line_, "a void argument");
            if (first) t = Type{promoted(a.type.scalar), a.type.width};
            else {
                if (a.type.is_vector() && t.is_vector() && a.type.width != t.width)
                    fail(line_, "arguments of " + std::to_string(t.width) + " and " + std::to_string(a.type.width) + " components");
                t = Type{common_scalar(t.scalar, a.type.scalar), std::max(t.width, a.type.width)};
            }
            first = false;
        }
        if (floats && !is_float(t.scalar)) t.scalar = Scalar::f32;
        return t;
    }

    Value elementwise(const std::vector<Value>& args, const Type& t, const Type& result, const std::function<OpFn(Scalar)>& fn) {
        std::vector<Value> c;
        for (const Value& a : args) c.push_back(convert(a, t));
        Value out{result, {}};
        const OpFn f = fn(t.scalar);
        if (!f) fail(line_, "a function on a " + type_name(t) + ", which it does not take");
        for (int k = 0; k < t.width; ++k) {
            const auto K = static_cast<std::size_t>(k);
            out.regs.push_back(one_op(f, c[0].regs[K], c.size() > 1 ? c[1].regs[K] : -1, c.size() > 2 ? c[2].regs[K] : -1));
        }
        return out;
    }

    Value builtin(const Expr& e) {
        std::string name = e.text;
        const int line = e.line;
        auto arity = [&](std::size_t n) {
            if (e.args.size() != n)
                fail(line, quoted(e.text) + " takes " + std::to_string(n) + " arguments, not " + std::to_string(e.args.size()));
        };
        if (name == "get_global_id" || name == "get_global_size") {
            arity(1);
            const long long k = constant_integer(*e.args[0]);
            if (k < 0 || k > 2) fail(line, quoted(name) + "(" + std::to_string(k) + "): the dimensions are 0, 1 and 2");
            if (name == "get_global_id") return Value{Type{Scalar::u64, 1}, {c_.id_registers[k]}};
            return constant_value(Scalar::u64, c_.global[k], 0);
        }
        if (name == "get_work_dim") {
            arity(0);
            return constant_value(Scalar::u32, 3, 0);
        }
        for (const char* prefix : {"native_", "half_"})
            if (name.rfind(prefix, 0) == 0) name = name.substr(std::string(prefix).size());
        std::vector<Value> args;
        for (const ExprPtr& a : e.args) args.push_back(expr(*a));
        line_ = line;
        static const std::map<std::string, Math1> m1 = {
            {"sqrt", Math1::sqrt},   {"rsqrt", Math1::rsqrt}, {"cbrt", Math1::cbrt},   {"exp", Math1::exp},
            {"exp2", Math1::exp2},   {"exp10", Math1::exp10}, {"expm1", Math1::expm1}, {"log", Math1::log},
            {"log2", Math1::log2},   {"log10", Math1::log10}, {"log1p", Math1::log1p}, {"sin", Math1::sin},
            {"cos", Math1::cos},     {"tan", Math1::tan},     {"asin", Math1::asin},   {"acos", Math1::acos},
            {"atan", Math1::atan},   {"sinh", Math1::sinh},   {"cosh", Math1::cosh},   {"tanh", Math1::tanh},
            {"asinh", Math1::asinh}, {"acosh", Math1::acosh}, {"atanh", Math1::atanh}, {"fabs", Math1::fabs},
            {"floor", Math1::floor}, {"ceil", Math1::ceil},   {"round", Math1::round}, {"trunc", Math1::trunc},
            {"rint", Math1::rint},   {"sign", Math1::sign},   {"erf", Math1::erf},     {"erfc", Math1::erfc},
            {"tgamma", Math1::tgamma}, {"lgamma", Math1::lgamma}};
        static const std::map<std::string, Math2> m2 = {
            {"pow", Math2::pow},     {"powr", Math2::powr},         {"atan2", Math2::atan2},
            {"hypot", Math2::hypot}, {"fmod", Math2::fmod},         {"fmin", Math2::fmin},
            {"fmax", Math2::fmax},   {"step", Math2::step},         {"copysign", Math2::copysign},
            {"fdim", Math2::fdim},   {"remainder", Math2::remainder}};
        static const std::map<std::string, Math2> relational = {
            {"isless", Math2::isless},           {"isgreater", Math2::isgreater},   {"islessequal", Math2::islessequal},
            {"isgreaterequal", Math2::isgreaterequal}, {"isequal", Math2::isequal}, {"isnotequal", Math2::isnotequal}};
        if (const auto i = m1.find(name); i != m1.end()) {
            arity(1);
            const Type t = widest(args, true);
            return elementwise(args, t, t, [&](Scalar s) { return ops::math1(i->second, s); });
        }
        if (name == "isnan" || name == "isinf" || name == "isfinite") {
            arity(1);
            const Type t = widest(args, true);
            const Type rt = t.is_vector() ? Type{mask_scalar(t.scalar), t.width} : Type{Scalar::i32, 1};
            const Math1 m = name == "isnan" ? Math1::isnan : name == "isinf" ? Math1::isinf : Math1::isfinite;
            if (!t.is_vector() && t.scalar == Scalar::f64) {
                // a scalar's answer is an int; the double's op gives a long
                Value v = elementwise(args, t, Type{Scalar::i64, 1}, [&](Scalar s) { return ops::math1(m, s, false); });
                return convert(v, rt);
            }
            return elementwise(args, t, rt, [&](Scalar s) { return ops::math1(m, s, t.is_vector()); });
        }
        if (const auto i = m2.find(name); i != m2.end()) {
            arity(2);
            const Type t = widest(args, true);
            return elementwise(args, t, t, [&](Scalar s) { return ops::math2(i->second, s); });
        }
        if (const auto i = relational.find(name); i != relational.end()) {
            arity(2);
            const Type t = widest(args, true);
            const Type rt = t.is_vector() ? Type{mask_scalar(t.scalar), t.width} : Type{Scalar::i32, 1};
            if (!t.is_vector() && t.scalar == Scalar::f64) {
                Value v = elementwise(args, t, Type{Scalar::i64, 1}, [&](Scalar s) { return ops::math2(i->second, s, false); });
                return convert(v, rt);
            }
            return elementwise(args, t, rt, [&](Scalar s) { return ops::math2(i->second, s, t.is_vector()); });
        }
        if (name == "min" || name == "max") {
            arity(2);
            const Type t = widest(args, false);
            return elementwise(args, t, t, [&](Scalar s) { return ops::math2(name == "min" ? Math2::min : Math2::max, s); });
        }
        if (name == "clamp") {
            arity(3);
            const Type t = widest(args, false);
            return elementwise(args, t, t, [&](Scalar s) { return ops::math3(Math3::clamp, s); });
        }
        if (name == "mix" || name == "fma" || name == "mad" || name == "smoothstep") {
            arity(3);
            const Type t = widest(args, true);
            const Math3 m = name == "mix" ? Math3::mix : name == "fma" ? Math3::fma : name == "mad" ? Math3::mad : Math3::smoothstep;
            return elementwise(args, t, t, [&](Scalar s) { return ops::math3(m, s); });
        }
        if (name == "abs") {
            arity(1);
            const Type t = widest(args, false);
            if (is_float(t.scalar)) return elementwise(args, t, t, [&](Scalar s) { return ops::math1(Math1::fabs, s); });
            Value v = elementwise(args, t, t, [&](Scalar s) { return ops::math1(Math1::iabs, s); });
            // abs of a signed integer is its unsigned type
            const Scalar u = t.scalar == Scalar::i32 ? Scalar::u32 : t.scalar == Scalar::i64 ? Scalar::u64 : t.scalar;
            v.type.scalar = u;
            return v;
        }
        if (name == "recip") {
            arity(1);
            const Type t = widest(args, true);
            Value one = constant_value(t.scalar, 0, 1.0);
            return arithmetic("/", one, convert(args[0], t));
        }
        if (name == "divide") {
            arity(2);
            const Type t = widest(args, true);
            return arithmetic("/", convert(args[0], t), convert(args[1], t));
        }
        if (name == "pown" || name == "rootn") {
            arity(2);
            Type t = widest({args[0]}, true);
            Value y = convert(args[1], Type{t.scalar, args[1].type.width});
            if (name == "rootn") {
                Value one = constant_value(t.scalar, 0, 1.0);
                y = arithmetic("/", one, y);
            }
            return elementwise({args[0], y}, t, t, [&](Scalar s) { return ops::math2(Math2::pow, s); });
        }
        if (name == "dot" || name == "length" || name == "fast_length" || name == "distance" ||
            name == "fast_distance" || name == "normalize" || name == "fast_normalize") {
            const bool two = name == "dot" || name == "distance" || name == "fast_distance";
            arity(two ? 2 : 1);
            const Type t = widest(args, true);
            Value a = convert(args[0], t);
            if (name == "distance" || name == "fast_distance") a = arithmetic("-", a, convert(args[1], t));
            Value b = name == "dot" ? convert(args[1], t) : a;
            const Scalar s = t.scalar;
            int sum = one_op(ops::binary(Binary::mul, s), a.regs[0], b.regs[0]);
            for (int k = 1; k < t.width; ++k) {
                const int p = one_op(ops::binary(Binary::mul, s), a.regs[static_cast<std::size_t>(k)], b.regs[static_cast<std::size_t>(k)]);
                sum = one_op(ops::binary(Binary::add, s), sum, p);
            }
            if (name == "dot") return Value{Type{s, 1}, {sum}};
            const int len = one_op(ops::math1(Math1::sqrt, s), sum);
            if (name == "length" || name == "fast_length" || name == "distance" || name == "fast_distance")
                return Value{Type{s, 1}, {len}};
            return arithmetic("/", a, Value{Type{s, 1}, {len}});
        }
        if (name == "cross") {
            arity(2);
            const Type t = widest(args, true);
            if (t.width < 3) fail(line, "cross of " + type_name(t) + "s");
            Value a = convert(args[0], t), b = convert(args[1], t);
            auto prod = [&](int i, int j) {
                return one_op(ops::binary(Binary::mul, t.scalar), a.regs[static_cast<std::size_t>(i)], b.regs[static_cast<std::size_t>(j)]);
            };
            Value out{t, {}};
            const int idx[3][2] = {{1, 2}, {2, 0}, {0, 1}};
            for (const auto& p : idx) out.regs.push_back(one_op(ops::binary(Binary::sub, t.scalar), prod(p[0], p[1]), prod(p[1], p[0])));
            if (t.width == 4) out.regs.push_back(constant_value(t.scalar, 0, 0).regs[0]);
            return out;
        }
        if (name == "select") {
            arity(3);
            const Type t = widest({args[0], args[1]}, false);
            Value a = convert(args[0], t), b = convert(args[1], t);
            const Value& c = args[2];
            if (c.type.is_void() || is_float(c.type.scalar)) fail(line, "select's third argument is a " + type_name(c.type) + ", not an integer");
            if (c.type.is_vector() != t.is_vector() || (c.type.is_vector() && c.type.width != t.width))
                fail(line, "select of " + type_name(t) + "s by a " + type_name(c.type));
            Value out{t, {}};
            for (int k = 0; k < t.width; ++k) {
                const auto K = static_cast<std::size_t>(k);
                const int m = mask();
                emit(t.is_vector() ? ops::sign_mask(c.type.scalar) : ops::to_mask(c.type.scalar), m, c.regs[K]);
                out.regs.push_back(one_op(ops::select(t.scalar), a.regs[K], b.regs[K], m));
            }
            return out;
        }
        if (name == "any" || name == "all") {
            arity(1);
            const Value& v = args[0];
            if (v.type.is_void() || is_float(v.type.scalar)) fail(line, quoted(name) + " of a " + type_name(v.type));
            int acc = -1;
            for (int r : v.regs) {
                const int m = mask();
                emit(ops::sign_mask(v.type.scalar), m, r);
                if (acc < 0) acc = m;
                else {
                    const int n = mask();
                    emit(name == "any" ? ops::mask_or() : ops::mask_and(), n, acc, m);
                    acc = n;
                }
            }
            const int d = temp();
            emit(ops::from_mask(), d, acc);
            return Value{Type{Scalar::i32, 1}, {d}};
        }
        if (name.rfind("convert_", 0) == 0) {
            arity(1);
            std::string rest = name.substr(8);
            bool sat = false;
            std::string rounding;
            for (const char* r : {"_rte", "_rtz", "_rtp", "_rtn"})
                if (rest.size() > 4 && rest.compare(rest.size() - 4, 4, r) == 0) rounding = r, rest.resize(rest.size() - 4);
            if (rest.size() > 4 && rest.compare(rest.size() - 4, 4, "_sat") == 0) sat = true, rest.resize(rest.size() - 4);
            (void)sat;  // figgen's conversions to integers saturate always
            std::optional<Type> to;
            for (const char* base : {"int", "uint", "long", "ulong", "float", "double"}) {
                const std::string b = base;
                if (rest == b) to = Type{common_scalar(b == "int" ? Scalar::i32 : b == "uint" ? Scalar::u32 : b == "long" ? Scalar::i64 : b == "ulong" ? Scalar::u64 : b == "float" ? Scalar::f32 : Scalar::f64, Scalar::i32), 1};
                else if (rest.size() == b.size() + 1 && rest.compare(0, b.size(), b) == 0 && rest.back() >= '2' && rest.back() <= '4') {
                    const Scalar s = b == "int" ? Scalar::i32 : b == "uint" ? Scalar::u32 : b == "long" ? Scalar::i64 : b == "ulong" ? Scalar::u64 : b == "float" ? Scalar::f32 : Scalar::f64;
                    to = Type{s, rest.back() - '0'};
                }
            }
            if (rest == "float") to = Type{Scalar::f32, 1};
            if (rest == "double") to = Type{Scalar::f64, 1};
            if (rest == "uint") to = Type{Scalar::u32, 1};
            if (rest == "ulong") to = Type{Scalar::u64, 1};
            if (!to) fail(line, quoted(e.text) + " is not a conversion figgen makes");
            Value v = args[0];
            if (v.type.is_void() || v.type.width != to->width)
                fail(line, quoted(e.text) + " of a " + type_name(v.type));
            if (is_float(v.type.scalar) && !is_float(to->scalar) && !rounding.empty() && rounding != "_rtz") {
                const Math1 m = rounding == "_rte" ? Math1::rint : rounding == "_rtp" ? Math1::ceil : Math1::floor;
                v = elementwise({v}, v.type, v.type, [&](Scalar s) { return ops::math1(m, s); });
            }
            Value out{*to, {}};
            for (int r : v.regs) {
                if (v.type.scalar == to->scalar) out.regs.push_back(r);
                else out.regs.push_back(one_op(ops::convert(v.type.scalar, to->scalar), r));
            }
            return out;
        }
        static const std::set<std::string> refused = {"barrier", "mem_fence", "read_mem_fence", "write_mem_fence",
                                                      "get_local_id", "get_local_size", "get_group_id", "get_num_groups",
                                                      "printf", "atomic_add", "atomic_inc", "atom_add", "async_work_group_copy"};
        if (refused.count(name))
            fail(line, quoted(e.text) + " is not one of the built-ins figgen's kernels may call: they run without "
                       "work groups, local memory, atomics or printing");
        fail(line, quoted(e.text) + " is neither a function of the kernel nor a built-in figgen knows");
    }

    // statements
    void declare(const Declaration& d) {
        for (const Declarator& n : d.names) {
            line_ = n.line;
            if (d.type.is_void()) fail(n.line, "a void variable");
            if (n.dims.empty()) {
                Symbol s;
                s.type = d.type;
                s.is_const = d.is_const || d.space == Space::constant;
                s.regs = variable(d.type);
                if (n.init) {
                    if (n.init->kind == Expr::Kind::list) fail(n.line, "a { } initialiser for " + quoted(n.name) + ", which is not an array");
                    Value v = expr(*n.init);
                    line_ = n.line;
                    if (v.type.is_vector() && !d.type.is_vector())
                        fail(n.line, "initialises " + quoted(n.name) + ", a " + type_name(d.type) + ", with a " + type_name(v.type));
                    Value c = convert(v, d.type);
                    for (std::size_t k = 0; k < s.regs.size(); ++k) emit(ops::copy(d.type.scalar), s.regs[k], c.regs[k]);
                } else {
                    for (int r : s.regs) emit_zero(d.type.scalar, r);
                }
                bind(n.name, std::move(s));
                continue;
            }
            long long count = 1;
            for (long long dim : n.dims) count *= dim;
            if (count * d.type.width > max_registers)
                fail(n.line, "the array " + quoted(n.name) + " has " + std::to_string(count * d.type.width) +
                                 " numbers: a work item keeps at most " + std::to_string(max_registers));
            ArrayInfo a;
            a.name = n.name;
            a.width = d.type.width;
            a.count = count;
            a.dims = n.dims;
            // consecutive registers: take fresh ones above every register in use
            a.base = c_.registers;
            c_.registers += static_cast<int>(count * d.type.width);
            if (c_.registers > max_registers)
                fail(n.line, "the kernel needs more than " + std::to_string(max_registers) + " registers a work item");
            c_.arrays.push_back(a);
            const int id = static_cast<int>(c_.arrays.size()) - 1;
            owned_arrays_.insert(id);
            std::vector<Value> values;
            if (n.init) {
                if (n.init->kind != Expr::Kind::list) fail(n.line, "the array " + quoted(n.name) + " is initialised without { }");
                flatten(*n.init, n.dims, 0, d.type, values, count);
            }
            for (long long i = 0; i < count; ++i)
                for (int k = 0; k < d.type.width; ++k) {
                    const int r = a.base + static_cast<int>(i) * d.type.width + k;
                    if (static_cast<std::size_t>(i) < values.size()) emit(ops::copy(d.type.scalar), r, values[static_cast<std::size_t>(i)].regs[static_cast<std::size_t>(k)]);
                    else emit_zero(d.type.scalar, r);
                }
            Symbol s;
            s.kind = Symbol::Kind::array;
            s.type = d.type;
            s.array = id;
            s.owner = true;
            s.is_const = d.is_const || d.space == Space::constant;
            bind(n.name, std::move(s));
        }
    }

    void emit_zero(Scalar s, int r) {
        Op zero;
        zero.fn = ops::constant(s);
        zero.dst = r;
        emit(zero);
    }

    // An initialiser's values in the array's order; nested braces for
    // each dimension, or a flat list.
    void flatten(const Expr& list, const std::vector<long long>& dims, std::size_t level, const Type& t, std::vector<Value>& out, long long count) {
        long long per = 1;
        for (std::size_t k = level + 1; k < dims.size(); ++k) per *= dims[k];
        const std::size_t start = out.size();
        for (const ExprPtr& item : list.args) {
            if (static_cast<long long>(out.size()) >= count) fail(item->line, "more initialisers than the array holds");
            if (item->kind == Expr::Kind::list) {
                if (level + 1 >= dims.size()) fail(item->line, "braces deeper than the array's dimensions");
                const std::size_t before = out.size();
                flatten(*item, dims, level + 1, t, out, count);
                // a row given short is filled with zeros
                while (static_cast<long long>(out.size() - before) < per) out.push_back(convert(int_value(0), t));
            } else {
                Value v = expr(*item);
                line_ = item->line;
                out.push_back(convert(v, t));
            }
        }
        (void)start;
    }

    void statement(const Stmt& s) {
        line_ = s.line;
        temps_.emplace_back();
        switch (s.kind) {
        case Stmt::Kind::expr: expr(*s.expr); break;
        case Stmt::Kind::declare: declare(s.declaration); break;
        case Stmt::Kind::block:
            scopes_.emplace_back();
            for (const StmtPtr& b : s.body) statement(*b);
            pop_scope();
            break;
        case Stmt::Kind::if_: {
            IfNode f;
            f.cond = condition(*s.expr);
            line_ = s.line;
            f.then_mask = mask();
            f.else_mask = mask();
            f.join = mask();
            const int outer = block_;
            f.then_block = sub_block(*s.body[0]);
            f.else_block = s.body.size() > 1 ? sub_block(*s.body[1]) : -1;
            block_ = outer;
            c_.ifs.push_back(f);
            Op op;
            op.fn = ops::if_node();
            op.aux = static_cast<int>(c_.ifs.size()) - 1;
            emit(op);
            break;
        }
        case Stmt::Kind::for_:
        case Stmt::Kind::while_:
        case Stmt::Kind::do_: loop(s); break;
        case Stmt::Kind::switch_: switch_statement(s); break;
        case Stmt::Kind::case_: fail(s.line, "a case label outside a switch's braces");
        case Stmt::Kind::break_: {
            if (targets_.empty()) fail(s.line, "break outside a loop or switch");
            jump(targets_.back().broken);
            break;
        }
        case Stmt::Kind::continue_: {
            int to = -1;
            for (auto t = targets_.rbegin(); t != targets_.rend() && to < 0; ++t) to = t->continued;
            if (to < 0) fail(s.line, "continue outside a loop");
            jump(to);
            break;
        }
        case Stmt::Kind::return_: {
            ++frames_.back().returns;
            const Frame f = frames_.back();  // a copy: calls in the value push frames
            if (s.expr) {
                Value v = expr(*s.expr);
                line_ = s.line;
                if (f.result.is_void()) {
                    if (!v.type.is_void()) fail(s.line, "returns a value from a void function");
                } else {
                    if (v.type.is_vector() && !f.result.is_vector())
                        fail(s.line, "returns a " + type_name(v.type) + " from a function of " + type_name(f.result));
                    Value c = convert(v, f.result);
                    for (std::size_t k = 0; k < c.regs.size(); ++k) emit(ops::assign(f.result.scalar), f.result_regs[k], c.regs[k]);
                }
            } else if (!f.result.is_void()) {
                fail(s.line, "returns no value from a function of " + type_name(f.result));
            }
            jump(f.returned);
            break;
        }
        case Stmt::Kind::empty: break;
        }
        release_temps();
    }

    void jump(int to) {
        Op op;
        op.fn = ops::jump();
        op.aux = to;
        emit(op);
    }

    int sub_block(const Stmt& s) {
        const int b = new_block();
        const int outer = block_;
        block_ = b;
        scopes_.emplace_back();
        statement(s);
        pop_scope();
        block_ = outer;
        return b;
    }

    void loop(const Stmt& s) {
        scopes_.emplace_back();
        LoopNode L;
        L.test_first = s.kind != Stmt::Kind::do_;
        if (s.kind == Stmt::Kind::for_ && s.body[0]) statement(*s.body[0]);
        line_ = s.line;
        L.lm = mask();
        L.exit = mask();
        L.broken = mask();
        L.continued = mask();
        const int outer = block_;
        L.cond_block = -1;
        L.cond = -1;
        if (s.expr) {
            L.cond_block = new_block();
            block_ = L.cond_block;
            temps_.emplace_back();
            L.cond = condition(*s.expr);
            release_temps();
            block_ = outer;
        }
        targets_.push_back({L.broken, L.continued});
        const Stmt& body = s.kind == Stmt::Kind::for_ ? *s.body[1] : *s.body[0];
        L.body = sub_block(body);
        targets_.pop_back();
        L.step = -1;
        if (s.step) {
            L.step = new_block();
            block_ = L.step;
            temps_.emplace_back();
            expr(*s.step);
            release_temps();
            block_ = outer;
        }
        line_ = s.line;
        c_.loops.push_back(L);
        Op op;
        op.fn = ops::loop_node();
        op.aux = static_cast<int>(c_.loops.size()) - 1;
        emit(op);
        pop_scope();
    }

    void switch_statement(const Stmt& s) {
        Value sel = expr(*s.expr);
        line_ = s.line;
        if (sel.type.is_void() || sel.type.is_vector() || is_float(sel.type.scalar))
            fail(s.line, "switch on a " + type_name(sel.type) + ": OpenCL C switches on integers");
        SwitchNode w;
        w.selector = convert(sel, Type{Scalar::i64, 1}).regs[0];
        w.entry = mask();
        w.enter = mask();
        w.fall = mask();
        w.broken = mask();
        const int outer = block_;
        targets_.push_back({w.broken, -1});
        scopes_.emplace_back();
        std::set<std::int64_t> labels;
        bool has_default = false;
        for (const StmtPtr& st : s.body[0]->body) {
            if (st->kind == Stmt::Kind::case_) {
                if (w.segments.empty() || !c_.blocks[static_cast<std::size_t>(w.segments.back().block)].ops.empty() ||
                    w.segments.back().has_body) {
                    SwitchNode::Segment seg;
                    seg.block = new_block();
                    w.segments.push_back(seg);
                }
                SwitchNode::Segment& seg = w.segments.back();
                if (st->expr) {
                    const long long v = constant_integer(*st->expr);
                    if (!labels.insert(v).second) fail(st->line, "the case " + std::to_string(v) + " is given twice");
                    seg.labels.push_back(v);
                } else {
                    if (has_default) fail(st->line, "two defaults in one switch");
                    has_default = true;
                    seg.is_default = true;
                }
                continue;
            }
            if (w.segments.empty()) fail(st->line, "a statement in a switch before its first case");
            w.segments.back().has_body = true;
            block_ = w.segments.back().block;
            statement(*st);
            block_ = outer;
        }
        pop_scope();
        targets_.pop_back();
        block_ = outer;
        line_ = s.line;
        c_.switches.push_back(w);
        Op op;
        op.fn = ops::switch_node();
        op.aux = static_cast<int>(c_.switches.size()) - 1;
        emit(op);
    }

    void kernel(const Function& f) {
        line_ = f.line;
        if (!f.result.is_void()) fail(f.line, "the kernel " + quoted(f.name) + " returns a value: kernels are void");
        if (f.parameters.size() != iface_.parameters.size())
            fail(f.line, "the kernel " + quoted(f.name) + " takes " + std::to_string(f.parameters.size()) +
                             " parameters; Ready passes it " + std::to_string(iface_.parameters.size()));
        block_ = 1;
        temps_.emplace_back();  // the values bound to parameters live through the kernel
        std::map<std::string, Symbol> params;
        for (std::size_t k = 0; k < f.parameters.size(); ++k) {
            const Declaration& d = f.parameters[k].declaration;
            const Binding& b = iface_.parameters[k];
            const std::string& name = d.names[0].name;
            line_ = f.parameters[k].line;
            if (b.kind == Binding::Kind::value) {
                if (d.pointer) fail(line_, "the kernel's parameter " + quoted(name) + " is a pointer; Ready passes it a number");
                Symbol s;
                s.type = d.type;
                s.is_const = true;
                s.regs = variable(d.type);
                Value v = constant_value(b.scalar, b.value, static_cast<double>(b.value));
                Value c = convert(v, d.type);
                for (std::size_t i = 0; i < s.regs.size(); ++i) emit(ops::copy(d.type.scalar), s.regs[i], c.regs[i]);
                params[name] = s;
                continue;
            }
            if (!d.pointer || d.space != Space::global)
                fail(line_, "the kernel's parameter " + quoted(name) + " is not a __global pointer; Ready passes it a buffer");
            if (d.type.scalar != b.scalar)
                fail(line_, "the kernel's buffer " + quoted(name) + " holds " + type_name(d.type) + "; Ready passes it " +
                                type_name(Type{b.scalar, 1}) + "s");
            BufferView v;
            v.name = name;
            v.parameter = static_cast<int>(k);
            v.output = b.kind == Binding::Kind::output;
            v.scalar = d.type.scalar;
            v.width = d.type.width;
            c_.buffers.push_back(v);
            Symbol s;
            s.kind = Symbol::Kind::buffer;
            s.type = d.type;
            s.view = static_cast<int>(c_.buffers.size()) - 1;
            s.is_const = d.is_const;
            params[name] = s;
        }
        Frame frame;
        frame.returned = mask();
        frames_.push_back(frame);
        scopes_.push_back(std::move(params));
        for (const StmtPtr& s : f.body->body) statement(*s);
        release_temps();
        pop_scope();
        frames_.pop_back();
    }

    const Program& prog_;
    const Interface& iface_;
    Compiled c_;
    int block_ = 0;
    int line_ = 0;
    int operations_ = 0;
    std::set<int> free_;
    std::set<int> owned_;
    std::set<int> owned_arrays_;
    std::vector<std::vector<int>> temps_;
    std::vector<std::map<std::string, Symbol>> scopes_;
    std::map<std::string, const Function*> functions_;
    std::vector<std::string> calls_;
    std::vector<Frame> frames_;
    std::vector<Target> targets_;
};

}  // namespace

Compiled compile(const Program& program, const Interface& iface) {
    Compiler c(program, iface);
    return c.run();
}

}  // namespace sim::kernel
