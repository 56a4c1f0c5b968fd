#pragma once
// The syntax tree of a kernel rule: a whole OpenCL C program as Ready's
// pattern files hold them (<rule type="kernel">), read by figgen's own
// grammar (sim/kernel/parse.cpp) and compiled by sim/kernel/compile.cpp
// into the lane programs sim/kernel/exec.cpp runs. Nothing here is ever
// handed to a compiler, a shell or a driver.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sim::kernel {

// What is wrong with a kernel's text, or what it did at run time: one
// line, naming the kernel's line.
struct KernelError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The scalar types OpenCL C's kernels use; size_t is u64.
enum class Scalar : std::uint8_t { b, i32, u32, i64, u64, f32, f64 };

// A value's type: a scalar, or a vector of 2, 3 or 4 of one; void.
struct Type {
    Scalar scalar = Scalar::i32;
    int width = 1;  // 1: a scalar; 2 to 4: a vector; 0: void
    bool operator==(const Type&) const = default;
    bool is_void() const { return width == 0; }
    bool is_vector() const { return width > 1; }
};

constexpr bool is_float(Scalar s) { return s == Scalar::f32 || s == Scalar::f64; }
constexpr bool is_signed(Scalar s) { return s == Scalar::i32 || s == Scalar::i64; }
constexpr int bytes_of(Scalar s) {
    return s == Scalar::i64 || s == Scalar::u64 || s == Scalar::f64 ? 8 : 4;
}
std::string type_name(const Type& t);

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

struct Expr {
    enum class Kind {
        integer,   // number: an integer literal of `type`
        real,      // number: a floating literal of `type`
        name,      // text
        index,     // args[0][args[1]]
        member,    // args[0].text (a swizzle)
        call,      // text(args...)
        cast,      // (type) args[0]
        vector,    // (type)(args...)
        unary,     // text args[0]: - + ! ~ ++ -- (prefix)
        postfix,   // args[0] text: ++ --
        binary,    // args[0] text args[1]
        assign,    // args[0] text args[1]: = += -= *= /= %= &= |= ^= <<= >>=
        ternary,   // args[0] ? args[1] : args[2]
        comma,     // args[0], args[1]
        list,      // { args... }: an initialiser
    };
    Kind kind;
    int line = 0;
    std::string text;
    Type type;
    std::uint64_t integer = 0;
    double real = 0;
    std::vector<ExprPtr> args;
};

// A declared variable, parameter or program-scope constant.
struct Declarator {
    int line = 0;
    std::string name;
    std::vector<long long> dims;  // array dimensions, outermost first; -1: [] (a parameter)
    ExprPtr init;                 // may be null
};

enum class Space { none, global, constant, local, private_ };

struct Declaration {
    Type type;
    bool is_const = false;
    Space space = Space::none;
    bool pointer = false;
    std::vector<Declarator> names;
};

struct Stmt;
using StmtPtr = std::unique_ptr<Stmt>;

struct Stmt {
    enum class Kind {
        expr,      // expr
        declare,   // declaration
        block,     // body
        if_,       // expr, body[0], body[1] (may be absent)
        for_,      // body[0] (init, may be null), expr (condition, may be null), step (may be null), body[1]
        while_,    // expr, body[0]
        do_,       // body[0], expr
        switch_,   // expr, body[0] (a block whose statements hold `case_` labels)
        case_,     // expr (null: default)
        break_,
        continue_,
        return_,   // expr (may be null)
        empty,
    };
    Kind kind;
    int line = 0;
    ExprPtr expr, step;
    Declaration declaration;
    std::vector<StmtPtr> body;
};

struct Parameter {
    int line = 0;
    Declaration declaration;  // one name
};

struct Function {
    int line = 0;
    Type result;
    std::string name;
    bool is_kernel = false;
    std::vector<Parameter> parameters;
    StmtPtr body;  // null: a prototype
};

struct Program {
    std::vector<Declaration> constants;  // program scope, in order
    std::vector<Function> functions;
};

// The kernel text as figgen reads it: preprocessed (comments, #define,
// #if and #ifdef; cl_khr_fp64 defined, as on a device with doubles) and
// parsed. Throws KernelError, naming the line, for anything else.
Program parse(const std::string& text);

}  // namespace sim::kernel
