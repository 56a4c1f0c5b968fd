#pragma once
// The syntax tree of a formula rule (sim/formula/rule.hpp): what
// sim/formula/parse.cpp reads from the formula's text with figgen's own
// grammar, a small part of OpenCL C, and what sim/formula/lower.cpp turns
// into row operations. Nothing here is ever handed to a compiler.

#include <memory>
#include <string>
#include <vector>

namespace sim::formula {

// Where in the formula's text: 1-based line and column.
struct Pos {
    int line = 1, column = 1;
};

// The declared types: float and double are the model's number type, as are
// float4 and double4 (one cell each here, four in Ready's blocks); int.
enum class Type { real, real4, integer };

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

struct Expr {
    enum class Kind {
        number,    // text: the literal as written; value; integer: an int literal
        name,      // text
        index,     // text[args[0]]
        call,      // text(args...)
        cast,      // (type) args[0]
        unary,     // op args[0]: - + !
        binary,    // args[0] op args[1]: + - * / % < > <= >= == != && ||
        ternary,   // args[0] ? args[1] : args[2]
    };
    Kind kind;
    Pos pos;
    std::string text;  // the name, the function, the operator, or the literal
    double value = 0;  // number
    bool integer = false;
    Type type = Type::real;  // cast
    std::vector<ExprPtr> args;
};

struct Stmt;
using StmtPtr = std::unique_ptr<Stmt>;

struct Declarator {
    Pos pos;
    std::string name;
    int array_size = 0;  // 0: not an array
    ExprPtr init;        // may be null
};

struct Stmt {
    enum class Kind {
        declare,  // type declarators (constant when is_const)
        assign,   // target (a name or name[index]) op value: = += -= *= /=, and ++ / -- as += 1 / -= 1
        block,    // body
        if_,      // condition, body[0], body[1] (else, may be absent)
        for_,     // init (may be null), condition (may be null), step (may be null), body[0]
        empty,
    };
    Kind kind;
    Pos pos;
    // declare
    Type type = Type::real;
    bool is_const = false;
    std::vector<Declarator> declarators;
    // assign
    ExprPtr target;  // a name or an index expression
    std::string op;  // "=", "+=", "-=", "*=", "/="
    ExprPtr value;
    // if_, for_
    ExprPtr condition;
    StmtPtr init, step;
    std::vector<StmtPtr> body;
};

// The parsed formula: its statements in order.
struct Formula {
    std::vector<StmtPtr> statements;
};

// The bounds every formula is held to, whatever its author wrote.
struct Limits {
    static constexpr std::size_t max_chars = 64 * 1024;  // the formula's text
    static constexpr int max_tokens = 20000;
    static constexpr int max_depth = 64;                  // nesting of expressions and statements
    static constexpr int max_array = 256;                 // elements of a local array
    static constexpr int max_unrolled = 20000;            // statements run after loops are unrolled
    static constexpr int max_operations = 50000;          // row operations of the compiled formula
};

// Parses `text` (a formula's code); throws FormulaError (sim/formula/rule.hpp)
// with the line and column of the first thing outside the grammar.
Formula parse(const std::string& text);

}  // namespace sim::formula
