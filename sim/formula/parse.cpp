// The formula's grammar (sim/formula/tree.hpp): a lexer and a recursive
// descent parser for the part of OpenCL C that Ready's formula rules use.
//
//   statement   := declaration ';' | assignment ';' | '{' statement* '}' | ';'
//                | 'if' '(' expr ')' statement ('else' statement)?
//                | 'for' '(' (declaration | assignment)? ';' expr? ';' assignment? ')' statement
//   declaration := 'const'? type name ('[' integer ']')? ('=' expr)? (',' ...)*
//   assignment  := target ('=' | '+=' | '-=' | '*=' | '/=') expr | target ('++' | '--') | ('++' | '--') target
//   target      := name ('[' expr ']')?
//   expr        := or ('?' expr ':' expr)?      or := and ('||' and)*    and := eq ('&&' eq)*
//   eq          := rel (('==' | '!=') rel)*     rel := add (('<' | '>' | '<=' | '>=') add)*
//   add         := mul (('+' | '-') mul)*       mul := unary (('*' | '/' | '%') unary)*
//   unary       := ('-' | '+' | '!') unary | '(' type ')' unary | primary
//   primary     := number | name | name '(' (expr (',' expr)*)? ')' | name '[' expr ']' | '(' expr ')'
//   type        := float | float4 | double | double4 | int
//
// Anything else (pointers, while, do, goto, break, return, functions of its
// own, swizzles, preprocessor lines, strings) is refused at its line and
// column.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "sim/formula/rule.hpp"
#include "sim/formula/tree.hpp"

namespace sim::formula {

namespace {

struct Token {
    enum class Kind { name, number, punct, end } kind;
    std::string text;
    Pos pos;
    double value = 0;
    bool integer = false;
};

bool is_type(const std::string& s) {
    return s == "float" || s == "float4" || s == "double" || s == "double4" || s == "int";
}

Type type_of(const std::string& s) {
    if (s == "int") return Type::integer;
    if (s == "float4" || s == "double4") return Type::real4;
    return Type::real;
}

// Words of C and OpenCL C that name something this grammar does not have.
bool is_refused_word(const std::string& s) {
    static const char* const words[] = {
        "while",    "do",       "goto",     "break",   "continue", "return",  "switch",   "case",
        "default",  "struct",   "union",    "enum",    "typedef",  "sizeof",  "void",     "char",
        "short",    "long",     "unsigned", "signed",  "bool",     "half",    "uint",     "uchar",
        "ushort",   "ulong",    "float2",   "float3",  "float8",   "float16", "double2",  "double3",
        "double8",  "double16", "int2",     "int3",    "int4",     "int8",    "int16",    "global",
        "__global", "local",    "__local",  "private", "__private", "constant", "__constant", "kernel",
        "__kernel", "volatile", "restrict", "static",  "extern",   "inline",  "register", "auto",
        "image2d_t", "sampler_t", "else"};
    for (const char* w : words)
        if (s == w) return true;
    return false;
}

std::vector<Token> lex(const std::string& text) {
    if (text.size() > Limits::max_chars)
        throw FormulaError({1, 1}, "the formula has " + std::to_string(text.size()) + " characters, more than the " +
                                       std::to_string(Limits::max_chars) + " allowed");
    std::vector<Token> tokens;
    int line = 1, column = 1;
    std::size_t i = 0;
    auto advance = [&](std::size_t n) {
        for (std::size_t k = 0; k < n && i < text.size(); ++k, ++i) {
            if (text[i] == '\n') ++line, column = 1;
            else ++column;
        }
    };
    while (i < text.size()) {
        const char c = text[i];
        const Pos pos{line, column};
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
            advance(1);
            continue;
        }
        if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && text[i] != '\n') advance(1);
            continue;
        }
        if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            const std::size_t end = text.find("*/", i + 2);
            if (end == std::string::npos) throw FormulaError(pos, "a comment /* is never closed");
            advance(end + 2 - i);
            continue;
        }
        if (static_cast<int>(tokens.size()) >= Limits::max_tokens)
            throw FormulaError(pos, "the formula has more than " + std::to_string(Limits::max_tokens) + " tokens");
        if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            std::size_t j = i;
            while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
            Token t{Token::Kind::name, text.substr(i, j - i), pos};
            if (t.text.size() > 64) throw FormulaError(pos, "a name longer than 64 characters");
            tokens.push_back(std::move(t));
            advance(j - i);
            continue;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) ||
            (c == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
            std::size_t j = i;
            bool integer = true;
            while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
            if (j < text.size() && (text[j] == 'x' || text[j] == 'X'))
                throw FormulaError(pos, "hexadecimal numbers are not supported");
            if (j < text.size() && text[j] == '.') {
                integer = false;
                ++j;
                while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
            }
            if (j < text.size() && (text[j] == 'e' || text[j] == 'E')) {
                std::size_t k = j + 1;
                if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
                if (k >= text.size() || !std::isdigit(static_cast<unsigned char>(text[k])))
                    throw FormulaError(pos, "a number's exponent has no digits");
                while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) ++k;
                integer = false;
                j = k;
            }
            const std::string digits = text.substr(i, j - i);
            if (j < text.size() && (text[j] == 'f' || text[j] == 'F')) {
                if (integer) throw FormulaError(pos, "an integer with a float suffix: write " + digits + ".0f");
                ++j;
            }
            if (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_'))
                throw FormulaError(pos, "a number followed by letters: " + text.substr(i, j + 1 - i));
            Token t{Token::Kind::number, text.substr(i, j - i), pos};
            t.integer = integer;
            t.value = std::strtod(digits.c_str(), nullptr);
            if (!std::isfinite(t.value)) throw FormulaError(pos, "the number " + digits + " is too large");
            if (integer && t.value > 2147483647.0)
                throw FormulaError(pos, "the integer " + digits + " does not fit an int");
            tokens.push_back(std::move(t));
            advance(j - i);
            continue;
        }
        static const char* const puncts[] = {"+=", "-=", "*=", "/=", "++", "--", "<=", ">=", "==", "!=", "&&",
                                             "||", "+",  "-",  "*",  "/",  "%",  "<",  ">",  "=",  "!",  "?",
                                             ":",  "(",  ")",  "[",  "]",  "{",  "}",  ",",  ";"};
        bool matched = false;
        for (const char* p : puncts) {
            const std::size_t n = std::char_traits<char>::length(p);
            if (text.compare(i, n, p) == 0) {
                tokens.push_back({Token::Kind::punct, p, pos});
                advance(n);
                matched = true;
                break;
            }
        }
        if (matched) continue;
        std::string shown(1, c);
        if (c == '#') throw FormulaError(pos, "preprocessor lines (#) are not supported");
        if (c == '.') throw FormulaError(pos, "swizzles and members (.x) are not supported");
        if (c == '"' || c == '\'') throw FormulaError(pos, "strings and characters are not supported");
        if (c == '&' || c == '|' || c == '^' || c == '~')
            throw FormulaError(pos, "bitwise operators (" + shown + ") are not supported");
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126)
            throw FormulaError(pos, "a character outside printable ASCII (code " +
                                        std::to_string(static_cast<unsigned char>(c)) + ")");
        throw FormulaError(pos, "'" + shown + "' is not part of the formula language");
    }
    tokens.push_back({Token::Kind::end, "", {line, column}});
    return tokens;
}

class Parser {
public:
    explicit Parser(std::vector<Token> tokens) : tokens_(std::move(tokens)) {}

    Formula formula() {
        Formula f;
        while (peek().kind != Token::Kind::end) f.statements.push_back(statement());
        return f;
    }

private:
    const Token& peek(int ahead = 0) const {
        const std::size_t at = std::min(next_ + static_cast<std::size_t>(ahead), tokens_.size() - 1);
        return tokens_[at];
    }
    const Token& take() {
        const Token& t = tokens_[next_];
        if (next_ + 1 < tokens_.size()) ++next_;
        return t;
    }
    bool is(const char* punct, int ahead = 0) const {
        return peek(ahead).kind == Token::Kind::punct && peek(ahead).text == punct;
    }
    bool is_word(const char* word) const { return peek().kind == Token::Kind::name && peek().text == word; }
    [[noreturn]] void fail(const Token& t, const std::string& what) const { throw FormulaError(t.pos, what); }
    static std::string shown(const Token& t) { return t.kind == Token::Kind::end ? "the end" : "'" + t.text + "'"; }
    void expect(const char* punct) {
        if (!is(punct)) fail(peek(), std::string("expected '") + punct + "', found " + shown(peek()));
        take();
    }

    // Nesting depth, held to Limits::max_depth.
    struct Deeper {
        Parser& p;
        Deeper(Parser& parser, const Token& at) : p(parser) {
            if (++p.depth_ > Limits::max_depth)
                p.fail(at, "nested more than " + std::to_string(Limits::max_depth) + " deep");
        }
        ~Deeper() { --p.depth_; }
    };

    bool at_type() const {
        if (peek().kind != Token::Kind::name) return false;
        if (is_type(peek().text)) return true;
        return peek().text == "const";
    }

    std::string name(const char* what) {
        const Token& t = peek();
        if (t.kind != Token::Kind::name) fail(t, std::string("expected ") + what + ", found " + shown(t));
        if (is_type(t.text) || t.text == "const" || t.text == "if" || t.text == "for" || is_refused_word(t.text))
            fail(t, std::string("expected ") + what + ", found the word '" + t.text + "'");
        return take().text;
    }

    StmtPtr statement() {
        const Token& at = peek();
        Deeper deeper(*this, at);
        auto s = std::make_unique<Stmt>();
        s->pos = at.pos;
        if (is(";")) {
            take();
            s->kind = Stmt::Kind::empty;
            return s;
        }
        if (is("{")) {
            take();
            s->kind = Stmt::Kind::block;
            while (!is("}")) {
                if (peek().kind == Token::Kind::end) fail(peek(), "a block { is never closed");
                s->body.push_back(statement());
            }
            take();
            return s;
        }
        if (is_word("if")) {
            take();
            s->kind = Stmt::Kind::if_;
            expect("(");
            s->condition = expression();
            expect(")");
            s->body.push_back(statement());
            if (is_word("else")) {
                take();
                s->body.push_back(statement());
            }
            return s;
        }
        if (is_word("for")) {
            take();
            s->kind = Stmt::Kind::for_;
            expect("(");
            if (!is(";")) s->init = at_type() ? declaration() : assignment();
            expect(";");
            if (!is(";")) s->condition = expression();
            expect(";");
            if (!is(")")) s->step = assignment();
            expect(")");
            s->body.push_back(statement());
            return s;
        }
        if (peek().kind == Token::Kind::name && is_refused_word(peek().text))
            fail(peek(), "'" + peek().text + "' is not supported in a formula");
        StmtPtr done = at_type() ? declaration() : assignment();
        expect(";");
        return done;
    }

    StmtPtr declaration() {
        auto s = std::make_unique<Stmt>();
        s->kind = Stmt::Kind::declare;
        s->pos = peek().pos;
        if (is_word("const")) {
            take();
            s->is_const = true;
        }
        if (peek().kind != Token::Kind::name || !is_type(peek().text))
            fail(peek(), "expected a type (float, float4, double, double4 or int), found " + shown(peek()));
        s->type = type_of(take().text);
        if (is_word("const")) take(), s->is_const = true;  // "float const x"
        for (;;) {
            Declarator d;
            d.pos = peek().pos;
            if (is("*")) fail(peek(), "pointers are not supported");
            d.name = name("a name");
            if (is("(")) fail(peek(), "functions of the formula's own are not supported");
            if (is("[")) {
                take();
                const Token& size = peek();
                if (size.kind != Token::Kind::number || !size.integer)
                    fail(size, "an array's size must be an integer written out, found " + shown(size));
                if (size.value < 1 || size.value > Limits::max_array)
                    fail(size, "an array of " + size.text + " elements: allowed 1 to " +
                                   std::to_string(Limits::max_array));
                d.array_size = static_cast<int>(size.value);
                take();
                expect("]");
                if (is("[")) fail(peek(), "arrays of arrays are not supported");
            }
            if (is("=")) {
                take();
                if (is("{")) fail(peek(), "array initialisers { ... } are not supported");
                d.init = expression();
            }
            s->declarators.push_back(std::move(d));
            if (!is(",")) break;
            take();
        }
        return s;
    }

    ExprPtr target() {
        const Token& at = peek();
        auto e = std::make_unique<Expr>();
        e->kind = Expr::Kind::name;
        e->pos = at.pos;
        e->text = name("a name to assign to");
        if (is("[")) {
            auto index = std::make_unique<Expr>();
            index->kind = Expr::Kind::index;
            index->pos = at.pos;
            index->text = e->text;
            take();
            index->args.push_back(expression());
            expect("]");
            return index;
        }
        return e;
    }

    StmtPtr assignment() {
        auto s = std::make_unique<Stmt>();
        s->kind = Stmt::Kind::assign;
        s->pos = peek().pos;
        auto one = [&](const Pos& pos) {
            auto e = std::make_unique<Expr>();
            e->kind = Expr::Kind::number;
            e->pos = pos;
            e->text = "1";
            e->value = 1;
            e->integer = true;
            return e;
        };
        if (is("++") || is("--")) {
            const Token& op = take();
            s->target = target();
            s->op = op.text == "++" ? "+=" : "-=";
            s->value = one(op.pos);
            return s;
        }
        s->target = target();
        if (is("++") || is("--")) {
            const Token& op = take();
            s->op = op.text == "++" ? "+=" : "-=";
            s->value = one(op.pos);
            return s;
        }
        if (is("=") || is("+=") || is("-=") || is("*=") || is("/=")) {
            s->op = take().text;
            s->value = expression();
            return s;
        }
        if (is("(")) fail(peek(), "a call on its own does nothing: only assignments and declarations are statements");
        fail(peek(), "expected an assignment (=, +=, -=, *=, /=, ++ or --), found " + shown(peek()));
    }

    ExprPtr make(Expr::Kind kind, const Token& at, std::string text) {
        auto e = std::make_unique<Expr>();
        e->kind = kind;
        e->pos = at.pos;
        e->text = std::move(text);
        return e;
    }

    ExprPtr expression() {
        const Token& at = peek();
        Deeper deeper(*this, at);
        ExprPtr condition = binary(0);
        if (!is("?")) return condition;
        const Token& q = take();
        auto e = make(Expr::Kind::ternary, q, "?");
        e->args.push_back(std::move(condition));
        e->args.push_back(expression());
        expect(":");
        e->args.push_back(expression());
        return e;
    }

    // Binary operators by precedence level, loosest first.
    ExprPtr binary(int level) {
        static const std::vector<std::vector<const char*>> levels = {
            {"||"}, {"&&"}, {"==", "!="}, {"<", ">", "<=", ">="}, {"+", "-"}, {"*", "/", "%"}};
        if (level == static_cast<int>(levels.size())) return unary();
        ExprPtr left = binary(level + 1);
        for (;;) {
            const char* found = nullptr;
            for (const char* op : levels[level])
                if (is(op)) found = op;
            if (!found) return left;
            const Token& op = take();
            auto e = make(Expr::Kind::binary, op, found);
            e->args.push_back(std::move(left));
            e->args.push_back(binary(level + 1));
            left = std::move(e);
        }
    }

    ExprPtr unary() {
        const Token& at = peek();
        Deeper deeper(*this, at);
        if (is("-") || is("+") || is("!")) {
            const Token& op = take();
            auto e = make(Expr::Kind::unary, op, op.text);
            e->args.push_back(unary());
            return e;
        }
        if (is("++") || is("--")) fail(at, "++ and -- are statements here, not values");
        if (is("(") && peek(1).kind == Token::Kind::name && is_type(peek(1).text) && is(")", 2)) {
            take();
            const Token& type = take();
            take();
            auto e = make(Expr::Kind::cast, type, type.text);
            e->type = type_of(type.text);
            if (is("(")) {
                // (float4)(x) is a cast of x; (float4)(x, y, z, w) gives each
                // cell of a block its own value, which one cell cannot.
                const Token& open = take();
                ExprPtr inner = expression();
                if (is(","))
                    fail(peek(), "a vector literal (" + type.text + ")(x, y, ...) is not supported: a cell is one value");
                expect(")");
                (void)open;
                e->args.push_back(std::move(inner));
                return e;
            }
            e->args.push_back(unary());
            return e;
        }
        return primary();
    }

    ExprPtr primary() {
        const Token& at = peek();
        if (at.kind == Token::Kind::number) {
            auto e = make(Expr::Kind::number, at, at.text);
            e->value = at.value;
            e->integer = at.integer;
            take();
            return e;
        }
        if (is("(")) {
            take();
            ExprPtr e = expression();
            expect(")");
            return e;
        }
        if (at.kind == Token::Kind::name) {
            const std::string word = name("a value");
            if (is("(")) {
                const Token& open = take();
                auto e = make(Expr::Kind::call, at, word);
                (void)open;
                if (!is(")"))
                    for (;;) {
                        e->args.push_back(expression());
                        if (e->args.size() > 8) fail(peek(), "a call with more than 8 arguments");
                        if (!is(",")) break;
                        take();
                    }
                expect(")");
                return e;
            }
            if (is("[")) {
                take();
                auto e = make(Expr::Kind::index, at, word);
                e->args.push_back(expression());
                expect("]");
                return e;
            }
            if (is(".")) fail(peek(), "members and swizzles are not supported");
            return make(Expr::Kind::name, at, word);
        }
        fail(at, "expected a value, found " + shown(at));
    }

    std::vector<Token> tokens_;
    std::size_t next_ = 0;
    int depth_ = 0;
};

}  // namespace

Formula parse(const std::string& text) {
    return Parser(lex(text)).formula();
}

}  // namespace sim::formula
