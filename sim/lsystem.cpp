#include "sim/lsystem.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "sim/check.hpp"

namespace sim {

namespace {

constexpr const char* allowed_symbols = "letters A-Z a-z and + - & ^ \\ / | [ ] ! { } . '";
constexpr std::uint64_t saturated = std::numeric_limits<std::uint64_t>::max();

std::uint64_t add(std::uint64_t a, std::uint64_t b) {
    return a > saturated - b ? saturated : a + b;
}

std::string strip_spaces(std::string_view text) {
    std::string out;
    for (char c : text)
        if (c != ' ' && c != '\t') out += c;
    return out;
}

// A rule or axiom as the message shows it: the text as written, quoted.
std::string quoted(std::string_view text) {
    std::string out = "\"";  // appended, not "\"" + text: GCC 12 warns of a false overlap there
    out.append(text);
    out += '"';
    return out;
}

// `name` and `value` name the text in the message: axiom "F]" or rules[1] "F -> F[".
// Brackets and braces are each balanced within every text, so they are in
// every string the system rewrites to: a successor replaces one symbol, and
// a balanced text put in place of one symbol keeps the whole balanced.
void check_text(std::string_view text, const std::string& name, const std::string& value) {
    int open = 0, polygons = 0;
    for (char c : text) {
        if (!lsystem_symbol(c))
            throw ParameterError(name, value, std::string(allowed_symbols) + " (unknown symbol '" + c + "')");
        open += c == '[' ? 1 : c == ']' ? -1 : 0;
        polygons += c == '{' ? 1 : c == '}' ? -1 : 0;
        if (open < 0 || polygons < 0) break;  // a ']' before its '[' pops an empty stack; a '}' closes nothing
    }
    if (open != 0)
        throw ParameterError(name, value,
                             "balanced brackets, every '[' with a later ']' and every ']' with an earlier '[' "
                             "(unbalanced brackets)");
    if (polygons != 0)
        throw ParameterError(name, value,
                             "balanced braces, every '{' (a polygon begins) with a later '}' (it ends) and every "
                             "'}' with an earlier '{' (unbalanced braces)");
}

void check_predecessor(char c, const std::string& name, const std::string& value) {
    if (!lsystem_symbol(c) || c == '[' || c == ']' || c == '{' || c == '}')
        throw ParameterError(name, value,
                             "a predecessor that is a letter or one of + - & ^ \\ / | ! . ' (the predecessor '" +
                                 std::string(1, c) + "' cannot be rewritten)");
}

// Symbols that occur anywhere in the system, in a fixed order, and each one's index.
struct Alphabet {
    std::vector<char> symbols;
    std::array<int, 256> index;
};

Alphabet alphabet_of(const LSystem& system) {
    std::array<bool, 256> seen{};
    auto note = [&](std::string_view text) {
        for (char c : text) seen[static_cast<unsigned char>(c)] = true;
    };
    note(system.axiom);
    for (const auto& [predecessor, successor] : system.rules) {
        note(std::string_view(&predecessor, 1));
        note(successor);
    }
    Alphabet a;
    a.index.fill(-1);
    for (int c = 0; c < 256; ++c)
        if (seen[static_cast<std::size_t>(c)]) {
            a.index[static_cast<std::size_t>(c)] = static_cast<int>(a.symbols.size());
            a.symbols.push_back(static_cast<char>(c));
        }
    return a;
}

using Counts = std::vector<std::uint64_t>;  // by alphabet index

void add_into(Counts& sum, const Counts& more) {
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = add(sum[i], more[i]);
}

std::map<char, std::uint64_t> as_map(const Alphabet& a, const Counts& counts) {
    std::map<char, std::uint64_t> out;
    for (std::size_t i = 0; i < counts.size(); ++i)
        if (counts[i] > 0) out[a.symbols[i]] = counts[i];
    return out;
}

std::uint64_t total(const std::map<char, std::uint64_t>& counts) {
    std::uint64_t sum = 0;
    for (const auto& [symbol, count] : counts) sum = add(sum, count);
    return sum;
}

// The counts of a text, given each symbol's counts in `each` (by alphabet index).
Counts counts_of(std::string_view text, const Alphabet& a, const std::vector<Counts>& each) {
    Counts sum(a.symbols.size(), 0);
    for (char c : text) add_into(sum, each[static_cast<std::size_t>(a.index[static_cast<unsigned char>(c)])]);
    return sum;
}

}  // namespace

bool lsystem_symbol(char c) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')) return true;
    return std::string_view("+-&^\\/|[]!{}.'").find(c) != std::string_view::npos;
}

// Each error names the text by its parameter: "axiom", or "rules[i]" for the i-th rule as given.
LSystem LSystem::parse(std::string_view axiom, const std::vector<std::string>& rules) {
    LSystem system;
    system.axiom = strip_spaces(axiom);
    if (system.axiom.empty()) throw ParameterError("axiom", quoted(axiom), "one or more symbols");
    check_text(system.axiom, "axiom", quoted(axiom));
    for (std::size_t i = 0; i < rules.size(); ++i) {
        const std::string& text = rules[i];
        const std::string name = "rules[" + std::to_string(i) + "]", value = quoted(text);
        const std::string rule = strip_spaces(text);
        std::size_t arrow = rule.find("->"), skip = 2;
        if (arrow == std::string::npos) arrow = rule.find('='), skip = 1;
        if (arrow == std::string::npos)
            throw ParameterError(name, value, "\"F -> successor\" or \"F = successor\" (the rule has no arrow)");
        const std::string predecessor = rule.substr(0, arrow), successor = rule.substr(arrow + skip);
        if (predecessor.size() != 1)
            throw ParameterError(name, value,
                                 "exactly one symbol before the arrow (the predecessor \"" + predecessor +
                                     "\" is not one symbol)");
        const char c = predecessor[0];
        check_predecessor(c, name, value);
        if (system.rules.count(c))
            throw ParameterError(name, value,
                                 "one rule per symbol, the system is deterministic (a second rule for '" +
                                     predecessor + "')");
        check_text(successor, name, value);
        system.rules[c] = successor;
    }
    return system;
}

void LSystem::validate() const {
    if (axiom.empty()) throw ParameterError("axiom", quoted(axiom), "one or more symbols");
    check_text(axiom, "axiom", quoted(axiom));
    for (const auto& [predecessor, successor] : rules) {
        const std::string value = quoted(std::string(1, predecessor) + " -> " + successor);
        check_predecessor(predecessor, "rules", value);
        check_text(successor, "rules", value);
    }
}

void LSystem::check_depth(int depth) const {
    require_integer("depth", depth, 0, max_depth);
}

LSystem::Successors LSystem::successor_table() const {
    Successors table{};
    for (const auto& [predecessor, successor] : rules) table[static_cast<unsigned char>(predecessor)] = &successor;
    return table;
}

// each[c] holds the counts of c's expansion at level k; level k + 1 sums its
// rule's symbols at level k. A fixed point (identity rules, saturation) ends
// the loop early, so max_depth costs no more than the first repeat.
std::map<char, std::uint64_t> LSystem::counts(int depth) const {
    check_depth(depth);
    const Alphabet a = alphabet_of(*this);
    const std::size_t n = a.symbols.size();
    std::vector<Counts> each(n, Counts(n, 0));
    for (std::size_t i = 0; i < n; ++i) each[i][i] = 1;
    for (int k = 1; k <= depth; ++k) {
        std::vector<Counts> next = each;
        for (const auto& [predecessor, successor] : rules)
            next[static_cast<std::size_t>(a.index[static_cast<unsigned char>(predecessor)])] =
                counts_of(successor, a, each);
        if (next == each) break;
        each = std::move(next);
    }
    return as_map(a, counts_of(axiom, a, each));
}

std::uint64_t LSystem::length(int depth) const {
    return total(counts(depth));
}

// Article reading: inner[c] holds the counts of R(rule_c, k), the string
// L(rule_c, k) walks; a symbol d of the rule contributes R(rule_d, k - 1)
// (when k - 1 > 0) and then d itself.
std::map<char, std::uint64_t> LSystem::counts_recursive(int depth) const {
    check_depth(depth);
    const Alphabet a = alphabet_of(*this);
    const std::size_t n = a.symbols.size();
    std::vector<Counts> unit(n, Counts(n, 0)), inner(n, Counts(n, 0));  // inner at level 0: nothing
    for (std::size_t i = 0; i < n; ++i) unit[i][i] = 1;
    for (int k = 1; k <= depth; ++k) {
        std::vector<Counts> with_self = unit;  // R(rule_d, k - 1) then d
        for (const auto& [predecessor, successor] : rules) {
            const auto i = static_cast<std::size_t>(a.index[static_cast<unsigned char>(predecessor)]);
            add_into(with_self[i], inner[i]);
        }
        std::vector<Counts> next = inner;
        for (const auto& [predecessor, successor] : rules)
            next[static_cast<std::size_t>(a.index[static_cast<unsigned char>(predecessor)])] =
                counts_of(successor, a, with_self);
        if (next == inner) break;
        inner = std::move(next);
    }
    std::vector<Counts> top = unit;  // the axiom: a symbol with a rule becomes R(rule, depth)
    for (const auto& [predecessor, successor] : rules) {
        const auto i = static_cast<std::size_t>(a.index[static_cast<unsigned char>(predecessor)]);
        top[i] = inner[i];
    }
    return as_map(a, counts_of(axiom, a, top));
}

std::uint64_t LSystem::length_recursive(int depth) const {
    return total(counts_recursive(depth));
}

// all[c] counts the `symbols` in c's expansion at level k, inside[c] only
// those within a brace pair of that expansion. Reading a successor with its
// own brace depth d, a symbol y adds all of y's when d > 0 (the pair encloses
// y's whole expansion) and inside[y] otherwise; braces are balanced in each
// text, so a pair never spans two successors.
std::uint64_t LSystem::count_enclosed(int depth, std::string_view symbols) const {
    check_depth(depth);
    const Alphabet a = alphabet_of(*this);
    const std::size_t n = a.symbols.size();
    std::vector<std::uint64_t> all(n, 0), inside(n, 0);
    for (std::size_t i = 0; i < n; ++i) all[i] = symbols.find(a.symbols[i]) != std::string_view::npos ? 1 : 0;
    auto read = [&](std::string_view text, std::uint64_t& sum_all, std::uint64_t& sum_inside) {
        sum_all = sum_inside = 0;
        int open = 0;
        for (char c : text) {
            const auto i = static_cast<std::size_t>(a.index[static_cast<unsigned char>(c)]);
            open += c == '{' ? 1 : 0;
            sum_all = add(sum_all, all[i]);
            sum_inside = add(sum_inside, open > 0 ? all[i] : inside[i]);
            open -= c == '}' ? 1 : 0;
        }
    };
    for (int k = 1; k <= depth; ++k) {
        std::vector<std::uint64_t> next_all = all, next_inside = inside;
        for (const auto& [predecessor, successor] : rules) {
            const auto i = static_cast<std::size_t>(a.index[static_cast<unsigned char>(predecessor)]);
            read(successor, next_all[i], next_inside[i]);
        }
        if (next_all == all && next_inside == inside) break;
        all = std::move(next_all);
        inside = std::move(next_inside);
    }
    std::uint64_t sum_all = 0, sum_inside = 0;
    read(axiom, sum_all, sum_inside);
    return sum_inside;
}

}  // namespace sim
