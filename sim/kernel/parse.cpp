// A kernel rule's text read by figgen's own grammar: a preprocessor of
// object-like macros and conditionals, a lexer and a recursive-descent
// parser of the part of OpenCL C that Ready's kernels are written in.
// Everything is bounded: the text's size, a macro's expansion, the
// nesting of expressions and statements.

#include <cctype>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>

#include "sim/kernel/tree.hpp"

namespace sim::kernel {

namespace {

constexpr std::size_t max_text = 1 << 20;      // bytes of a kernel's text
constexpr std::size_t max_tokens = 1 << 19;    // after macros are expanded
constexpr int max_depth = 200;                 // nesting of expressions and statements
constexpr int max_expansion = 64;              // macros within macros

[[noreturn]] void fail(int line, const std::string& what) {
    throw KernelError("kernel line " + std::to_string(line) + ": " + what);
}

// A short, printable quote of a word of the text.
std::string quoted(const std::string& s) {
    std::string out;
    for (char c : s.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    if (s.size() > 40) out += "...";
    return "\"" + out + "\"";
}

struct Token {
    enum class Kind { word, number, punct, string, end } kind = Kind::end;
    std::string text;
    int line = 0;
};

bool word_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The tokens of one line (comments gone already).
void lex_line(const std::string& s, int line, std::vector<Token>& out) {
    static const char* puncts[] = {"<<=", ">>=", "...", "++", "--", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||",
                                   "+=",  "-=",  "*=",  "/=", "%=", "&=", "|=", "^=", "->", "##"};
    std::size_t i = 0;
    while (i < s.size()) {
        const char c = s[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
            continue;
        }
        Token t;
        t.line = line;
        if (word_start(c)) {
            std::size_t j = i;
            while (j < s.size() && word_char(s[j])) ++j;
            t.kind = Token::Kind::word;
            t.text = s.substr(i, j - i);
            i = j;
        } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                   (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
            std::size_t j = i;
            while (j < s.size()) {
                const char d = s[j];
                if (word_char(d) || d == '.') ++j;
                else if ((d == '+' || d == '-') && (s[j - 1] == 'e' || s[j - 1] == 'E') &&
                         !(s[i] == '0' && i + 1 < s.size() && (s[i + 1] == 'x' || s[i + 1] == 'X')))
                    ++j;
                else break;
            }
            t.kind = Token::Kind::number;
            t.text = s.substr(i, j - i);
            i = j;
        } else if (c == '"') {
            std::size_t j = i + 1;
            while (j < s.size() && s[j] != '"') j += s[j] == '\\' ? 2 : 1;
            if (j >= s.size()) fail(line, "a string that does not end on its line");
            t.kind = Token::Kind::string;
            t.text = s.substr(i + 1, j - i - 1);
            i = j + 1;
        } else {
            t.kind = Token::Kind::punct;
            for (const char* p : puncts) {
                const std::size_t n = std::char_traits<char>::length(p);
                if (s.compare(i, n, p) == 0) {
                    t.text = p;
                    break;
                }
            }
            if (t.text.empty()) {
                if (std::string("{}[]()<>;:,.?+-*/%&|^!~=#").find(c) == std::string::npos)
                    fail(line, "the character " + quoted(std::string(1, c)) + " is not part of OpenCL C here");
                t.text = std::string(1, c);
            }
            i += t.text.size();
        }
        out.push_back(std::move(t));
    }
}

// The text as lines with comments blanked (so lines keep their numbers)
// and continuations joined (the joined line keeps the first's number).
std::vector<std::pair<int, std::string>> logical_lines(const std::string& text) {
    std::string clean;
    clean.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        if (text.compare(i, 2, "//") == 0) {
            while (i < text.size() && text[i] != '\n') ++i;
        } else if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            const std::size_t stop = end == std::string::npos ? text.size() : end + 2;
            for (; i < stop; ++i) clean += text[i] == '\n' ? '\n' : ' ';
            if (end == std::string::npos) break;
        } else if (text[i] == '"') {
            // a string (of #error) is kept whole, comment marks and all
            clean += text[i++];
            while (i < text.size() && text[i] != '"' && text[i] != '\n') {
                if (text[i] == '\\' && i + 1 < text.size() && text[i + 1] != '\n') clean += text[i++];
                clean += text[i++];
            }
            if (i < text.size() && text[i] == '"') clean += text[i++];
        } else {
            clean += text[i++];
        }
    }
    std::vector<std::pair<int, std::string>> lines;
    int line = 1;
    std::string current;
    int start = 1;
    for (std::size_t i = 0; i <= clean.size(); ++i) {
        if (i == clean.size() || clean[i] == '\n') {
            if (!current.empty() && current.back() == '\\') {
                current.pop_back();
                ++line;
                continue;
            }
            lines.emplace_back(start, current);
            current.clear();
            start = ++line;
        } else if (clean[i] != '\r') {
            current += clean[i];
        }
    }
    return lines;
}

// The preprocessor: object-like macros and #if, #ifdef, #ifndef, #elif,
// #else, #endif, #error, #pragma (ignored), #undef.
class Preprocessor {
public:
    std::vector<Token> run(const std::string& text) {
        if (text.size() > max_text)
            throw KernelError("the kernel is " + std::to_string(text.size()) + " bytes: figgen reads at most " +
                              std::to_string(max_text));
        macros_["cl_khr_fp64"] = {Token{Token::Kind::number, "1", 0}};
        macros_["__OPENCL_VERSION__"] = {Token{Token::Kind::number, "120", 0}};
        macros_["__OPENCL_C_VERSION__"] = {Token{Token::Kind::number, "120", 0}};
        macros_["CL_VERSION_1_2"] = {Token{Token::Kind::number, "120", 0}};
        macros_["__ENDIAN_LITTLE__"] = {Token{Token::Kind::number, "1", 0}};
        for (const auto& [line, s] : logical_lines(text)) {
            std::size_t i = 0;
            while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
            if (i < s.size() && s[i] == '#') directive(line, s.substr(i + 1));
            else if (active()) {
                std::vector<Token> raw;
                lex_line(s, line, raw);
                for (const Token& t : raw) expand(t, out_, 0);
            }
            if (out_.size() > max_tokens) fail(line, "the kernel expands to more than " + std::to_string(max_tokens) + " tokens");
        }
        if (!conditions_.empty()) fail(conditions_.back().line, "an #if without its #endif");
        Token end;
        end.line = out_.empty() ? 1 : out_.back().line;
        out_.push_back(end);
        return std::move(out_);
    }

private:
    struct Condition {
        int line;
        bool parent_active, taken, active;
    };

    bool active() const { return conditions_.empty() || conditions_.back().active; }

    void expand(const Token& t, std::vector<Token>& out, int depth) {
        if (t.kind == Token::Kind::word) {
            const auto m = macros_.find(t.text);
            if (m != macros_.end() && !expanding_.count(t.text)) {
                if (depth >= max_expansion) fail(t.line, "macros nest more than " + std::to_string(max_expansion) + " deep");
                expanding_.insert(t.text);
                for (Token u : m->second) {
                    u.line = t.line;
                    expand(u, out, depth + 1);
                    if (out.size() > max_tokens) fail(t.line, "the kernel expands to more than " + std::to_string(max_tokens) + " tokens");
                }
                expanding_.erase(t.text);
                return;
            }
        }
        out.push_back(t);
    }

    void directive(int line, const std::string& rest) {
        std::vector<Token> toks;
        std::size_t i = 0;
        while (i < rest.size() && std::isspace(static_cast<unsigned char>(rest[i]))) ++i;
        std::size_t j = i;
        while (j < rest.size() && word_char(rest[j])) ++j;
        const std::string name = rest.substr(i, j - i);
        const std::string body = rest.substr(j);
        if (name == "if" || name == "ifdef" || name == "ifndef") {
            bool value = false;
            if (active()) {
                if (name == "if") value = evaluate(line, body);
                else {
                    lex_line(body, line, toks);
                    if (toks.size() != 1 || toks[0].kind != Token::Kind::word) fail(line, "#" + name + " takes one name");
                    value = macros_.count(toks[0].text) == (name == "ifdef" ? 1u : 0u);
                }
            }
            if (conditions_.size() >= 64) fail(line, "#if nests more than 64 deep");
            conditions_.push_back({line, active(), value, active() && value});
        } else if (name == "elif") {
            if (conditions_.empty()) fail(line, "#elif without #if");
            Condition& c = conditions_.back();
            const bool value = c.parent_active && !c.taken && evaluate(line, body);
            c.active = value;
            c.taken = c.taken || value;
        } else if (name == "else") {
            if (conditions_.empty()) fail(line, "#else without #if");
            Condition& c = conditions_.back();
            c.active = c.parent_active && !c.taken;
            c.taken = true;
        } else if (name == "endif") {
            if (conditions_.empty()) fail(line, "#endif without #if");
            conditions_.pop_back();
        } else if (!active()) {
            return;
        } else if (name == "define") {
            lex_line(body, line, toks);
            if (toks.empty() || toks[0].kind != Token::Kind::word) fail(line, "#define takes a name");
            std::size_t after = body.find(toks[0].text) + toks[0].text.size();
            if (after < body.size() && body[after] == '(')
                fail(line, "#define " + quoted(toks[0].text) + " takes arguments: figgen reads macros without them");
            macros_[toks[0].text] = std::vector<Token>(toks.begin() + 1, toks.end());
            if (macros_.size() > 10000) fail(line, "more than 10000 macros");
        } else if (name == "undef") {
            lex_line(body, line, toks);
            if (toks.size() != 1 || toks[0].kind != Token::Kind::word) fail(line, "#undef takes one name");
            macros_.erase(toks[0].text);
        } else if (name == "error") {
            lex_line(body, line, toks);
            fail(line, "#error " + (toks.empty() ? std::string("\"\"") : quoted(toks[0].text)));
        } else if (name == "pragma" || name.empty()) {
            // OPENCL EXTENSION and the like: doubles are always there
        } else {
            fail(line, "the directive #" + quoted(name) + " is not one figgen reads (#define, #undef, #if, #ifdef, "
                       "#ifndef, #elif, #else, #endif, #error, #pragma)");
        }
    }

    // #if's expression: defined, integers, macros, ! && || == != < > <= >= + - ( ).
    bool evaluate(int line, const std::string& body) {
        std::vector<Token> raw, toks;
        lex_line(body, line, raw);
        for (std::size_t i = 0; i < raw.size(); ++i) {
            if (raw[i].kind == Token::Kind::word && raw[i].text == "defined") {
                bool paren = i + 1 < raw.size() && raw[i + 1].text == "(";
                const std::size_t n = i + (paren ? 2 : 1);
                if (n >= raw.size() || raw[n].kind != Token::Kind::word) fail(line, "defined takes a name");
                toks.push_back({Token::Kind::number, macros_.count(raw[n].text) ? "1" : "0", line});
                i = n + (paren ? 1 : 0);
                if (paren && (i >= raw.size() || raw[i].text != ")")) fail(line, "defined( without its )");
            } else {
                expand(raw[i], toks, 0);
            }
        }
        std::size_t at = 0;
        const long long v = condition(toks, at, line, 0);
        if (at != toks.size()) fail(line, "#if's expression has more after " + quoted(toks[at - 1].text));
        return v != 0;
    }

    long long condition(const std::vector<Token>& t, std::size_t& at, int line, int prec) {
        long long left = primary(t, at, line);
        static const std::map<std::string, int> precs = {{"||", 1}, {"&&", 2}, {"==", 3}, {"!=", 3}, {"<", 4},
                                                         {">", 4},  {"<=", 4}, {">=", 4}, {"+", 5},  {"-", 5}};
        while (at < t.size()) {
            const auto p = precs.find(t[at].text);
            if (p == precs.end() || p->second <= prec) break;
            const std::string op = t[at++].text;
            const long long right = condition(t, at, line, p->second);
            if (op == "||") left = left || right;
            else if (op == "&&") left = left && right;
            else if (op == "==") left = left == right;
            else if (op == "!=") left = left != right;
            else if (op == "<") left = left < right;
            else if (op == ">") left = left > right;
            else if (op == "<=") left = left <= right;
            else if (op == ">=") left = left >= right;
            else if (op == "+") left = static_cast<long long>(static_cast<unsigned long long>(left) + static_cast<unsigned long long>(right));
            else left = static_cast<long long>(static_cast<unsigned long long>(left) - static_cast<unsigned long long>(right));
        }
        return left;
    }

    long long primary(const std::vector<Token>& t, std::size_t& at, int line) {
        if (at >= t.size()) fail(line, "#if's expression ends too soon");
        const Token& k = t[at++];
        if (k.text == "!") return !primary(t, at, line);
        if (k.text == "-") return -primary(t, at, line);
        if (k.text == "(") {
            const long long v = condition(t, at, line, 0);
            if (at >= t.size() || t[at].text != ")") fail(line, "#if's ( without its )");
            ++at;
            return v;
        }
        if (k.kind == Token::Kind::word) return 0;  // a name no macro defines
        if (k.kind == Token::Kind::number) return std::strtoll(k.text.c_str(), nullptr, 0);
        fail(line, "#if's expression has " + quoted(k.text));
    }

    std::map<std::string, std::vector<Token>> macros_;
    std::set<std::string> expanding_;
    std::vector<Condition> conditions_;
    std::vector<Token> out_;
};

std::optional<Type> type_word(const std::string& w) {
    static const std::map<std::string, Scalar> scalars = {
        {"bool", Scalar::b},     {"int", Scalar::i32},    {"uint", Scalar::u32},  {"long", Scalar::i64},
        {"ulong", Scalar::u64},  {"size_t", Scalar::u64}, {"float", Scalar::f32}, {"double", Scalar::f64},
    };
    if (w == "void") return Type{Scalar::i32, 0};
    const auto s = scalars.find(w);
    if (s != scalars.end()) return Type{s->second, 1};
    for (const char* base : {"int", "uint", "long", "ulong", "float", "double"}) {
        const std::string b = base;
        if (w.size() == b.size() + 1 && w.compare(0, b.size(), b) == 0 && w.back() >= '2' && w.back() <= '4')
            return Type{scalars.at(b), w.back() - '0'};
    }
    return std::nullopt;
}

// Words of C and OpenCL C that figgen's grammar leaves out, named when met.
bool refused_word(const std::string& w) {
    static const std::set<std::string> words = {
        "goto",   "struct",  "union",    "typedef", "enum",    "sizeof",   "__local",   "local",   "extern",
        "static", "char",    "uchar",    "short",   "ushort",  "half",     "image2d_t", "image3d_t", "sampler_t",
        "event_t", "volatile", "register", "auto",  "signed",  "__attribute__", "asm", "__asm__"};
    if (words.count(w)) return true;
    for (const char* v : {"char", "uchar", "short", "ushort", "half", "int", "uint", "long", "ulong", "float", "double"}) {
        const std::string b = v;
        if (w.size() > b.size() && w.compare(0, b.size(), b) == 0) {
            const std::string n = w.substr(b.size());
            const bool small = b == "char" || b == "uchar" || b == "short" || b == "ushort" || b == "half";
            if (n == "8" || n == "16" || (small && (n == "2" || n == "3" || n == "4"))) return true;
        }
    }
    return false;
}

class Parser {
public:
    explicit Parser(std::vector<Token> toks) : t_(std::move(toks)) {}

    Program program() {
        Program p;
        while (!at_end()) {
            if (accept(";")) continue;
            const int line = peek().line;
            bool is_kernel = false, is_const = false;
            Space space = Space::none;
            for (;;) {
                const std::string& w = peek().text;
                if (w == "__kernel" || w == "kernel") is_kernel = true;
                else if (w == "inline" || w == "__inline") {
                } else if (w == "const") is_const = true;
                else if (w == "__constant" || w == "constant") space = Space::constant;
                else if (w == "__global" || w == "global") space = Space::global;
                else if (w == "__private" || w == "private") space = Space::private_;
                else break;
                next();
            }
            const Type type = type_name(line);
            const bool pointer = accept("*");
            const Token name = expect_word("a name");
            if (peek().text == "(") {
                if (pointer) fail(line, "a function that returns a pointer");
                if (space != Space::none) fail(line, "a function in an address space");
                p.functions.push_back(function(line, type, name.text, is_kernel));
                if (p.functions.size() > 1000) fail(line, "more than 1000 functions");
                continue;
            }
            if (is_kernel) fail(line, "__kernel on " + quoted(name.text) + ", which is not a function");
            if (pointer) fail(line, "a pointer at program scope (" + quoted(name.text) + ")");
            if (space != Space::constant && !is_const)
                fail(line, "the program-scope variable " + quoted(name.text) +
                               " is not __constant: OpenCL C's program scope holds constants alone");
            Declaration d;
            d.type = type;
            d.is_const = true;
            d.space = Space::constant;
            declarators(d, name);
            expect(";");
            p.constants.push_back(std::move(d));
            if (p.constants.size() > 10000) fail(line, "more than 10000 program-scope constants");
        }
        return p;
    }

private:
    const Token& peek(std::size_t k = 0) const { return t_[std::min(at_ + k, t_.size() - 1)]; }
    bool at_end() const { return peek().kind == Token::Kind::end; }
    const Token& next() {
        const Token& t = peek();
        if (at_ < t_.size() - 1) ++at_;
        return t;
    }
    bool accept(const std::string& s) {
        if (peek().kind != Token::Kind::string && peek().kind != Token::Kind::end && peek().text == s) {
            next();
            return true;
        }
        return false;
    }
    void expect(const std::string& s) {
        if (!accept(s)) fail(peek().line, "expected " + quoted(s) + " but found " + found());
    }
    std::string found() const { return at_end() ? "the end of the kernel" : quoted(peek().text); }
    Token expect_word(const std::string& what) {
        if (peek().kind != Token::Kind::word) fail(peek().line, "expected " + what + " but found " + found());
        if (type_word(peek().text) || refused_word(peek().text)) fail(peek().line, "expected " + what + " but found the type word " + found());
        return next();
    }

    bool is_type_start() const {
        const std::string& w = peek().text;
        if (peek().kind != Token::Kind::word) return false;
        if (refused_word(w)) fail(peek().line, quoted(w) + " is not part of the OpenCL C that figgen reads");
        return type_word(w) || w == "const" || w == "__private" || w == "private" || w == "__global" || w == "global" ||
               w == "__constant" || w == "constant" || w == "unsigned";
    }

    Type type_name(int line) {
        if (peek().kind == Token::Kind::word && refused_word(peek().text))
            fail(peek().line, quoted(peek().text) + " is not part of the OpenCL C that figgen reads");
        if (accept("unsigned")) {
            if (accept("int")) return Type{Scalar::u32, 1};
            if (accept("long")) return Type{Scalar::u64, 1};
            return Type{Scalar::u32, 1};
        }
        if (peek().kind != Token::Kind::word) fail(line, "expected a type but found " + found());
        const auto t = type_word(peek().text);
        if (!t) fail(peek().line, "expected a type but found " + found());
        next();
        return *t;
    }

    Function function(int line, Type result, const std::string& name, bool is_kernel) {
        Function f;
        f.line = line;
        f.result = result;
        f.name = name;
        f.is_kernel = is_kernel;
        expect("(");
        if (!(peek().text == "void" && peek(1).text == ")")) {
            while (peek().text != ")") {
                Parameter p;
                p.line = peek().line;
                Declaration& d = p.declaration;
                qualifiers(d);
                d.type = type_name(p.line);
                qualifiers(d);
                if (d.type.is_void()) fail(p.line, "a void parameter");
                d.pointer = accept("*");
                qualifiers(d);
                accept("restrict");
                accept("__restrict");
                Declarator n;
                n.line = peek().line;
                n.name = expect_word("a parameter's name").text;
                if (accept("[")) {
                    if (!accept("]")) {
                        parse_expr();
                        expect("]");
                    }
                    d.pointer = true;
                }
                d.names.push_back(std::move(n));
                f.parameters.push_back(std::move(p));
                if (f.parameters.size() > 64) fail(line, "more than 64 parameters");
                if (!accept(",")) break;
            }
        } else {
            next();
        }
        expect(")");
        if (accept(";")) return f;
        f.body = block();
        return f;
    }

    void qualifiers(Declaration& d) {
        for (;;) {
            const std::string& w = peek().text;
            if (w == "const") d.is_const = true;
            else if (w == "__global" || w == "global") d.space = Space::global;
            else if (w == "__constant" || w == "constant") d.space = Space::constant;
            else if (w == "__private" || w == "private") d.space = Space::private_;
            else if (w == "__read_only" || w == "__write_only" || w == "read_only" || w == "write_only")
                fail(peek().line, quoted(w) + " belongs to images, which figgen's kernels do not take");
            else break;
            next();
        }
    }

    void declarators(Declaration& d, Token first) {
        for (;;) {
            Declarator n;
            n.line = first.line;
            n.name = first.text;
            while (accept("[")) {
                const int line = peek().line;
                ExprPtr size = parse_expr();
                expect("]");
                n.dims.push_back(constant_size(*size, line));
                if (n.dims.size() > 4) fail(line, "an array of more than 4 dimensions");
            }
            if (accept("=")) n.init = peek().text == "{" ? init_list() : assignment();
            d.names.push_back(std::move(n));
            if (!accept(",")) break;
            first = expect_word("a name");
        }
    }

    // An array's size: an integer literal, or +-*/ of them (macros are
    // expanded already).
    long long constant_size(const Expr& e, int line) {
        const long long v = fold(e, line);
        if (v < 1 || v > (1 << 20)) fail(line, "an array of " + std::to_string(v) + " elements: figgen allows 1 to 1048576");
        return v;
    }
    long long fold(const Expr& e, int line) {
        if (e.kind == Expr::Kind::integer) return static_cast<long long>(e.integer & 0x7fffffffffffLL);
        if (e.kind == Expr::Kind::binary) {
            const long long a = fold(*e.args[0], line), b = fold(*e.args[1], line);
            if (e.text == "+") return a + b;
            if (e.text == "-") return a - b;
            if (e.text == "*") return a * b;
            if (e.text == "/" && b != 0) return a / b;
        }
        fail(line, "an array's size must be a constant integer");
    }

    ExprPtr init_list() {
        const int line = peek().line;
        expect("{");
        auto e = std::make_unique<Expr>();
        e->kind = Expr::Kind::list;
        e->line = line;
        if (++depth_ > max_depth) fail(line, "braces nest more than " + std::to_string(max_depth) + " deep");
        while (peek().text != "}") {
            e->args.push_back(peek().text == "{" ? init_list() : assignment());
            if (e->args.size() > (1u << 20)) fail(line, "an initialiser of more than 1048576 values");
            if (!accept(",")) break;
        }
        --depth_;
        expect("}");
        return e;
    }

    StmtPtr block() {
        const int line = peek().line;
        expect("{");
        auto s = std::make_unique<Stmt>();
        s->kind = Stmt::Kind::block;
        s->line = line;
        if (++depth_ > max_depth) fail(line, "blocks nest more than " + std::to_string(max_depth) + " deep");
        while (!accept("}")) {
            if (at_end()) fail(line, "the block opened here does not close");
            s->body.push_back(statement());
        }
        --depth_;
        return s;
    }

    StmtPtr statement() {
        auto s = std::make_unique<Stmt>();
        s->line = peek().line;
        if (++depth_ > max_depth) fail(s->line, "statements nest more than " + std::to_string(max_depth) + " deep");
        const std::string w = peek().kind == Token::Kind::word || peek().kind == Token::Kind::punct ? peek().text : "";
        if (w == "{") {
            --depth_;
            return block();
        }
        if (accept(";")) {
            s->kind = Stmt::Kind::empty;
        } else if (accept("if")) {
            s->kind = Stmt::Kind::if_;
            expect("(");
            s->expr = parse_expr();
            expect(")");
            s->body.push_back(statement());
            if (accept("else")) s->body.push_back(statement());
        } else if (accept("for")) {
            s->kind = Stmt::Kind::for_;
            expect("(");
            if (accept(";")) s->body.push_back(nullptr);
            else s->body.push_back(simple_statement(true));
            if (peek().text != ";") s->expr = parse_expr();
            expect(";");
            if (peek().text != ")") s->step = parse_expr();
            expect(")");
            s->body.push_back(statement());
        } else if (accept("while")) {
            s->kind = Stmt::Kind::while_;
            expect("(");
            s->expr = parse_expr();
            expect(")");
            s->body.push_back(statement());
        } else if (accept("do")) {
            s->kind = Stmt::Kind::do_;
            s->body.push_back(statement());
            if (!accept("while")) fail(peek().line, "do without its while");
            expect("(");
            s->expr = parse_expr();
            expect(")");
            expect(";");
        } else if (accept("switch")) {
            s->kind = Stmt::Kind::switch_;
            expect("(");
            s->expr = parse_expr();
            expect(")");
            s->body.push_back(block());
        } else if (accept("case")) {
            s->kind = Stmt::Kind::case_;
            s->expr = ternary();
            expect(":");
        } else if (accept("default")) {
            s->kind = Stmt::Kind::case_;
            expect(":");
        } else if (accept("break")) {
            s->kind = Stmt::Kind::break_;
            expect(";");
        } else if (accept("continue")) {
            s->kind = Stmt::Kind::continue_;
            expect(";");
        } else if (accept("return")) {
            s->kind = Stmt::Kind::return_;
            if (peek().text != ";") s->expr = parse_expr();
            expect(";");
        } else {
            --depth_;
            return simple_statement(true);
        }
        --depth_;
        return s;
    }

    // A declaration or an expression, with its ;.
    StmtPtr simple_statement(bool semicolon) {
        auto s = std::make_unique<Stmt>();
        s->line = peek().line;
        if (is_type_start()) {
            s->kind = Stmt::Kind::declare;
            Declaration& d = s->declaration;
            qualifiers(d);
            d.type = type_name(s->line);
            qualifiers(d);
            if (d.type.is_void()) fail(s->line, "a void variable");
            if (peek().text == "*") fail(s->line, "a pointer variable: figgen's kernels index their buffers and arrays");
            if (d.space == Space::global) fail(s->line, "a __global variable inside a function");
            declarators(d, expect_word("a name"));
        } else {
            s->kind = Stmt::Kind::expr;
            s->expr = parse_expr();
        }
        if (semicolon) expect(";");
        return s;
    }

    ExprPtr make(Expr::Kind kind, int line, std::string text = {}) {
        auto e = std::make_unique<Expr>();
        e->kind = kind;
        e->line = line;
        e->text = std::move(text);
        return e;
    }

    ExprPtr parse_expr() {
        ExprPtr e = assignment();
        while (peek().text == ",") {
            const int line = next().line;
            ExprPtr c = make(Expr::Kind::comma, line, ",");
            c->args.push_back(std::move(e));
            c->args.push_back(assignment());
            e = std::move(c);
        }
        return e;
    }

    ExprPtr assignment() {
        if (++depth_ > max_depth) fail(peek().line, "an expression nests more than " + std::to_string(max_depth) + " deep");
        ExprPtr left = ternary();
        static const std::set<std::string> ops = {"=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>="};
        if (peek().kind == Token::Kind::punct && ops.count(peek().text)) {
            const Token& op = next();
            ExprPtr e = make(Expr::Kind::assign, op.line, op.text);
            e->args.push_back(std::move(left));
            e->args.push_back(assignment());
            left = std::move(e);
        }
        --depth_;
        return left;
    }

    ExprPtr ternary() {
        ExprPtr c = binary(0);
        if (peek().text != "?") return c;
        const int line = next().line;
        if (++depth_ > max_depth) fail(line, "an expression nests more than " + std::to_string(max_depth) + " deep");
        ExprPtr e = make(Expr::Kind::ternary, line, "?");
        e->args.push_back(std::move(c));
        e->args.push_back(parse_expr());
        expect(":");
        e->args.push_back(ternary());
        --depth_;
        return e;
    }

    static int precedence(const std::string& op) {
        static const std::map<std::string, int> p = {
            {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5},  {"==", 6}, {"!=", 6}, {"<", 7},  {">", 7},
            {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9},  {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
        const auto i = p.find(op);
        return i == p.end() ? -1 : i->second;
    }

    ExprPtr binary(int min_prec) {
        ExprPtr left = unary();
        for (;;) {
            if (peek().kind != Token::Kind::punct) break;
            const int prec = precedence(peek().text);
            if (prec < 0 || prec <= min_prec) break;
            const Token& op = next();
            if (++depth_ > max_depth) fail(op.line, "an expression nests more than " + std::to_string(max_depth) + " deep");
            ExprPtr e = make(Expr::Kind::binary, op.line, op.text);
            e->args.push_back(std::move(left));
            e->args.push_back(binary(prec));
            --depth_;
            left = std::move(e);
        }
        return left;
    }

    ExprPtr unary() {
        const Token& t = peek();
        if (++depth_ > max_depth) fail(t.line, "an expression nests more than " + std::to_string(max_depth) + " deep");
        ExprPtr out;
        if (t.kind == Token::Kind::punct && (t.text == "-" || t.text == "+" || t.text == "!" || t.text == "~" ||
                                             t.text == "++" || t.text == "--")) {
            const Token& op = next();
            out = make(Expr::Kind::unary, op.line, op.text);
            out->args.push_back(unary());
        } else if (t.kind == Token::Kind::punct && (t.text == "*" || t.text == "&")) {
            fail(t.line, "pointers (" + quoted(t.text) + "): figgen's kernels index their buffers and arrays");
        } else if (t.text == "(" && peek(1).kind == Token::Kind::word &&
                   (type_word(peek(1).text) || peek(1).text == "unsigned" || refused_word(peek(1).text))) {
            const int line = next().line;
            const Type type = type_name(line);
            expect(")");
            if (peek().text == "(" && type.is_vector()) {
                next();
                out = make(Expr::Kind::vector, line);
                out->type = type;
                while (peek().text != ")") {
                    out->args.push_back(assignment());
                    if (out->args.size() > 16) fail(line, "a vector literal of more than 16 values");
                    if (!accept(",")) break;
                }
                expect(")");
                if (out->args.empty()) fail(line, "an empty vector literal");
                out = postfix(std::move(out));
            } else {
                out = make(Expr::Kind::cast, line);
                out->type = type;
                out->args.push_back(unary());
            }
        } else {
            out = postfix(primary());
        }
        --depth_;
        return out;
    }

    ExprPtr postfix(ExprPtr e) {
        for (int chained = 0;; ++chained) {
            if (chained > max_depth) fail(peek().line, "more than " + std::to_string(max_depth) + " indices, members and increments in a row");
            const Token& t = peek();
            if (t.kind != Token::Kind::punct) break;
            if (t.text == "[") {
                const int line = next().line;
                ExprPtr i = make(Expr::Kind::index, line);
                i->args.push_back(std::move(e));
                i->args.push_back(parse_expr());
                expect("]");
                e = std::move(i);
            } else if (t.text == ".") {
                const int line = next().line;
                if (peek().kind != Token::Kind::word) fail(line, "expected a vector's components after . but found " + found());
                ExprPtr m = make(Expr::Kind::member, line, next().text);
                m->args.push_back(std::move(e));
                e = std::move(m);
            } else if (t.text == "++" || t.text == "--") {
                const Token& op = next();
                ExprPtr p = make(Expr::Kind::postfix, op.line, op.text);
                p->args.push_back(std::move(e));
                e = std::move(p);
            } else if (t.text == "->") {
                fail(t.line, "-> (structs and pointers): not part of the OpenCL C figgen reads");
            } else {
                break;
            }
        }
        return e;
    }

    ExprPtr primary() {
        const Token& t = next();
        if (t.kind == Token::Kind::number) return number(t);
        if (t.kind == Token::Kind::word) {
            if (refused_word(t.text) || type_word(t.text))
                fail(t.line, quoted(t.text) + " here is not part of the OpenCL C that figgen reads");
            if (peek().text == "(") {
                next();
                ExprPtr c = make(Expr::Kind::call, t.line, t.text);
                while (peek().text != ")") {
                    c->args.push_back(assignment());
                    if (c->args.size() > 64) fail(t.line, "a call with more than 64 arguments");
                    if (!accept(",")) break;
                }
                expect(")");
                return c;
            }
            return make(Expr::Kind::name, t.line, t.text);
        }
        if (t.text == "(") {
            ExprPtr e = parse_expr();
            expect(")");
            return e;
        }
        fail(t.line, t.kind == Token::Kind::end ? std::string("the kernel ends inside an expression")
                                                : "expected a value but found " + quoted(t.text));
    }

    ExprPtr number(const Token& t) {
        std::string s = t.text;
        const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
        const bool real = !hex && (s.find_first_of(".eE") != std::string::npos);
        if (real) {
            ExprPtr e = make(Expr::Kind::real, t.line, s);
            bool single = false;
            if (s.back() == 'f' || s.back() == 'F') single = true, s.pop_back();
            else if (s.back() == 'h' || s.back() == 'H') fail(t.line, "the half literal " + quoted(t.text));
            char* end = nullptr;
            const double v = std::strtod(s.c_str(), &end);
            if (end != s.c_str() + s.size()) fail(t.line, "the number " + quoted(t.text) + " is not one OpenCL C reads");
            e->type = Type{single ? Scalar::f32 : Scalar::f64, 1};
            e->real = single ? static_cast<double>(std::strtof(s.c_str(), nullptr)) : v;
            return e;
        }
        bool u = false, l = false;
        while (!s.empty() && (s.back() == 'u' || s.back() == 'U' || s.back() == 'l' || s.back() == 'L')) {
            if (s.back() == 'u' || s.back() == 'U') u = true;
            else l = true;
            s.pop_back();
        }
        if (!hex && s.size() > 1 && (s.back() == 'f' || s.back() == 'F'))
            fail(t.line, "the number " + quoted(t.text) + ": an integer with an f suffix");
        errno = 0;
        char* end = nullptr;
        const bool octal = !hex && s.size() > 1 && s[0] == '0';
        const unsigned long long v = std::strtoull(s.c_str(), &end, hex ? 16 : octal ? 8 : 10);
        if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
            fail(t.line, "the number " + quoted(t.text) + " is not one OpenCL C reads");
        ExprPtr e = make(Expr::Kind::integer, t.line, t.text);
        e->integer = v;
        // C's rule: the first of int, (uint,) long, ulong that holds it
        Scalar type;
        if (!l && !u && v <= 0x7fffffffULL) type = Scalar::i32;
        else if (!l && (u || hex || octal) && v <= 0xffffffffULL) type = Scalar::u32;
        else if (!u && v <= 0x7fffffffffffffffULL) type = Scalar::i64;
        else type = Scalar::u64;
        e->type = Type{type, 1};
        return e;
    }

    std::vector<Token> t_;
    std::size_t at_ = 0;
    int depth_ = 0;
};

}  // namespace

std::string type_name(const Type& t) {
    if (t.is_void()) return "void";
    static const char* names[] = {"bool", "int", "uint", "long", "ulong", "float", "double"};
    std::string n = names[static_cast<int>(t.scalar)];
    if (t.width > 1) n += std::to_string(t.width);
    return n;
}

Program parse(const std::string& text) {
    for (char c : text)
        if (c == '\0') throw KernelError("the kernel holds a NUL character");
    Preprocessor pp;
    Parser parser(pp.run(text));
    return parser.program();
}

}  // namespace sim::kernel
