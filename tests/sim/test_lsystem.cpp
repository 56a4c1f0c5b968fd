#include <catch2/catch.hpp>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/check.hpp"
#include "sim/lsystem.hpp"

using sim::LSystem;

namespace {

using Stream = std::vector<std::pair<char, int>>;  // (symbol, level)

// Parallel rewriting as in the textbook, building every string: the symbols
// of a successor written at step k get level depth - k.
Stream naive_rewrite(const LSystem& system, int depth) {
    Stream s;
    for (char c : system.axiom) s.push_back({c, depth});
    for (int k = 1; k <= depth; ++k) {
        Stream next;
        for (auto [c, level] : s) {
            const auto rule = system.rules.find(c);
            if (rule == system.rules.end())
                next.push_back({c, level});
            else
                for (char d : rule->second) next.push_back({d, depth - k});
        }
        s = std::move(next);
    }
    return s;
}

// The article's turtle code with the drawing replaced by writing symbols:
//   def f(n): if n > 0: L(F, n)
//   def L(s, n): for c in s: ... 'F': f(n-1); fd(d)
// generalised to any symbol with a rule, with the axiom read as f(depth).
void article_L(const LSystem& system, const std::string& s, int n, Stream& out);
void article_f(const LSystem& system, char c, int n, Stream& out) {
    if (n > 0) article_L(system, system.rules.at(c), n, out);
}
void article_L(const LSystem& system, const std::string& s, int n, Stream& out) {
    for (char c : s) {
        if (system.rules.count(c)) article_f(system, c, n - 1, out);
        out.push_back({c, n});
    }
}
Stream naive_article(const LSystem& system, int depth) {
    Stream out;
    for (char c : system.axiom) {
        if (system.rules.count(c))
            article_f(system, c, depth, out);
        else
            out.push_back({c, depth});
    }
    return out;
}

Stream streamed(const LSystem& system, int depth, bool article) {
    Stream out;
    auto visit = [&](char c, int level) { out.push_back({c, level}); };
    if (article)
        system.expand_recursive(depth, visit);
    else
        system.expand(depth, visit);
    return out;
}

std::map<char, std::uint64_t> counts_of(const Stream& s) {
    std::map<char, std::uint64_t> out;
    for (auto [c, level] : s) ++out[c];
    return out;
}

std::uint64_t pow6(int n) {
    std::uint64_t p = 1;
    for (int k = 0; k < n; ++k) p *= 6;
    return p;
}

const LSystem club_moss = LSystem::parse("F", {"F -> FF+[+F-F]-[-F+F]"});
const LSystem apple = LSystem::parse("X", {"X -> FF-[[X]+X]+F[+FX]-X", "F -> F"});
const LSystem abop_apple = LSystem::parse("X", {"X -> F-[[X]+X]+F[+FX]-X", "F -> FF"});

// Systems for the comparisons: the club moss, both apple trees, ABOP Fig
// 1.24 (a) and (d), an erasing rule, a 3-D plant and a rule on a non-letter.
std::vector<LSystem> systems() {
    return {club_moss,
            apple,
            abop_apple,
            LSystem::parse("F", {"F -> F[+F]F[-F]F"}),
            LSystem::parse("X", {"X -> F[+X]F[-X]+X", "F -> FF"}),
            LSystem::parse("AB", {"A -> AB[+A]", "B -> "}),
            LSystem::parse("A", {"A -> [&FL!A]/////[&FL!A]///////[&FL!A]", "F -> S/////F", "S -> FL", "L -> [^^f]"}),
            LSystem::parse("F+F", {"F -> F-F", "+ -> +|"})};
}

}  // namespace

TEST_CASE("F -> FF doubles the length at each depth", "[lsystem]") {
    const LSystem doubling = LSystem::parse("F", {"F -> FF"});
    for (int n = 0; n <= 63; ++n) {
        CHECK(doubling.length(n) == std::uint64_t{1} << n);
        CHECK(doubling.counts(n).at('F') == std::uint64_t{1} << n);
    }
    CHECK(doubling.length(64) == std::numeric_limits<std::uint64_t>::max());  // saturates
    CHECK(doubling.length(LSystem::max_depth) == std::numeric_limits<std::uint64_t>::max());
}

TEST_CASE("Club moss rewrite counts follow 6^n F in 3 * 6^n - 2 symbols", "[lsystem]") {
    for (int n = 0; n <= 20; ++n) {
        const auto counts = club_moss.counts(n);
        CHECK(counts.at('F') == pow6(n));
        CHECK(club_moss.length(n) == 3 * pow6(n) - 2);
        // 10 of each successor's 16 symbols are not F: 2 (6^n - 1) of them in all
        CHECK(club_moss.length(n) - counts.at('F') == 2 * (pow6(n) - 1));
    }
}

TEST_CASE("Club moss article counts follow 6 (6^n - 1) / 5 F in 16 (6^n - 1) / 5 symbols", "[lsystem]") {
    for (int n = 0; n <= 20; ++n) {
        const auto counts = club_moss.counts_recursive(n);
        const std::uint64_t f = counts.count('F') ? counts.at('F') : 0;
        CHECK(f == 6 * (pow6(n) - 1) / 5);
        CHECK(club_moss.length_recursive(n) == 16 * (pow6(n) - 1) / 5);
    }
    CHECK(club_moss.counts_recursive(3).at('F') == 258);  // the article's figure: 6 + 36 + 216
    const Stream s = streamed(club_moss, 3, true);
    std::map<int, int> by_level;
    for (auto [c, level] : s)
        if (c == 'F') ++by_level[level];
    CHECK(by_level == std::map<int, int>{{1, 216}, {2, 36}, {3, 6}});
}

TEST_CASE("Streamed expansion equals a naive rewrite symbol by symbol", "[lsystem]") {
    for (const LSystem& system : systems())
        for (int depth = 0; depth <= 5; ++depth) {
            INFO("axiom " << system.axiom << " depth " << depth);
            const Stream expected = naive_rewrite(system, depth);
            const Stream got = streamed(system, depth, false);
            REQUIRE(got.size() == expected.size());
            CHECK(got == expected);
            CHECK(system.length(depth) == expected.size());
            CHECK(system.counts(depth) == counts_of(expected));
        }
}

TEST_CASE("Streamed article expansion equals the article recursion symbol by symbol", "[lsystem]") {
    for (const LSystem& system : systems())
        for (int depth = 0; depth <= 5; ++depth) {
            INFO("axiom " << system.axiom << " depth " << depth);
            const Stream expected = naive_article(system, depth);
            const Stream got = streamed(system, depth, true);
            REQUIRE(got.size() == expected.size());
            CHECK(got == expected);
            CHECK(system.length_recursive(depth) == expected.size());
            CHECK(system.counts_recursive(depth) == counts_of(expected));
        }
}

TEST_CASE("The article stream at depth 1 is the rule and at depth 0 is empty", "[lsystem]") {
    Stream one;
    for (char c : std::string("FF+[+F-F]-[-F+F]")) one.push_back({c, 1});
    CHECK(streamed(club_moss, 1, true) == one);
    CHECK(streamed(club_moss, 0, true).empty());
    CHECK(streamed(club_moss, 0, false) == Stream{{'F', 0}});
    // depth 2 opens with f(1) then the F drawn at level 2
    const Stream two = streamed(club_moss, 2, true);
    CHECK(Stream(two.begin(), two.begin() + 17) == [] {
        Stream s = {};
        for (char c : std::string("FF+[+F-F]-[-F+F]")) s.push_back({c, 1});
        s.push_back({'F', 2});
        return s;
    }());
}

TEST_CASE("Apple trees expand without building strings", "[lsystem]") {
    // The article's apple tree at depth 4 and ABOP's at depth 5, against the naive rewrite.
    CHECK(apple.length(4) == naive_rewrite(apple, 4).size());
    CHECK(abop_apple.length(5) == naive_rewrite(abop_apple, 5).size());
    // ABOP's successor of X has 18 symbols: 4 X, 3 F and 11 others. So
    // X_n = 4^n, F_n = 2 F_(n-1) + 3 X_(n-1) = 3 (4^n - 2^n) / 2 and the
    // others number 11 (4^n - 1) / 3.
    for (int n = 0; n <= 12; ++n) {
        const std::uint64_t x = std::uint64_t{1} << (2 * n), two = std::uint64_t{1} << n;
        const auto counts = abop_apple.counts(n);
        CHECK(counts.at('X') == x);
        CHECK((n == 0 ? counts.count('F') == 0 : counts.at('F') == 3 * (x - two) / 2));
        CHECK(abop_apple.length(n) == x + 3 * (x - two) / 2 + 11 * (x - 1) / 3);
    }
    // Depth 7: the length comes from the counts alone; streaming it keeps
    // at most depth + 1 frames and no string.
    const std::uint64_t length7 = abop_apple.length(7);
    CHECK(length7 == 100'839);  // 16,384 X + 24,384 F + 60,071 others
    std::uint64_t streamed_symbols = 0, f = 0;
    abop_apple.expand(7, [&](char c, int) {
        ++streamed_symbols;
        f += c == 'F';
    });
    CHECK(streamed_symbols == length7);
    CHECK(f == abop_apple.counts(7).at('F'));
}

TEST_CASE("Parse accepts arrows and equals signs and ignores spaces", "[lsystem]") {
    const LSystem a = LSystem::parse(" X ", {"X = F [ +X ] -X", "F->FF"});
    CHECK(a.axiom == "X");
    CHECK(a.rules == std::map<char, std::string>{{'X', "F[+X]-X"}, {'F', "FF"}});
    const LSystem erase = LSystem::parse("AB", {"B ->"});
    CHECK(erase.rules.at('B').empty());
    CHECK(erase.length(1) == 1);
}

TEST_CASE("Parse errors name the problem and what is allowed", "[lsystem]") {
    using Catch::Contains;
    CHECK_THROWS_AS(LSystem::parse("F", {"F -> F["}), std::invalid_argument);
    CHECK_THROWS_AS(LSystem::parse("F", {"F -> F["}), sim::ParameterError);
    CHECK_THROWS_WITH(LSystem::parse("F", {"F -> F["}),
                      Contains("rules[0] = \"F -> F[\" is not allowed: balanced brackets") &&
                          Contains("unbalanced brackets"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"F -> F]["}), Contains("unbalanced brackets"));
    CHECK_THROWS_WITH(LSystem::parse("F]", {}),
                      Contains("axiom = \"F]\" is not allowed") && Contains("unbalanced brackets"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"F FF"}), Contains("rules[0] = \"F FF\"") && Contains("has no arrow"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"FF -> F"}),
                      Contains("predecessor \"FF\" is not one symbol") && Contains("exactly one symbol"));
    CHECK_THROWS_WITH(LSystem::parse("F", {" -> F"}), Contains("predecessor \"\" is not one symbol"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"F -> FF", "F = F"}),
                      Contains("rules[1] = \"F = F\"") && Contains("a second rule for 'F'"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"F -> F#F"}),
                      Contains("unknown symbol '#'") && Contains("is not allowed: letters A-Z a-z"));
    CHECK_THROWS_WITH(LSystem::parse("F#", {}), Contains("axiom = \"F#\"") && Contains("unknown symbol '#'"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"[ -> F"}), Contains("the predecessor '[' cannot be rewritten"));
    CHECK_THROWS_WITH(LSystem::parse("", {}), "axiom = \"\" is not allowed: one or more symbols");
    // one line each
    try {
        LSystem::parse("F", {"F -> F["});
    } catch (const std::invalid_argument& e) {
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
    }
}

TEST_CASE("Malformed polygons are refused when the system is read", "[lsystem][polygon]") {
    using Catch::Contains;
    const std::string balanced = "balanced braces, every '{' (a polygon begins) with a later '}' (it ends)";
    CHECK_THROWS_WITH(LSystem::parse("A", {"A -> F{-f+f"}),
                      Contains("rules[0] = \"A -> F{-f+f\" is not allowed: " + balanced) &&
                          Contains("(unbalanced braces)"));
    CHECK_THROWS_WITH(LSystem::parse("A", {"A -> F}f{"}), Contains("rules[0] = \"A -> F}f{\"") && Contains(balanced));
    CHECK_THROWS_WITH(LSystem::parse("{F", {}), Contains("axiom = \"{F\" is not allowed: " + balanced));
    CHECK_THROWS_WITH(LSystem::parse("F}", {}), Contains("axiom = \"F}\"") && Contains(balanced));
    // Open in one text and closed in another: refused too, as a bracket is.
    CHECK_THROWS_WITH(LSystem::parse("X}", {"X -> {F"}), Contains(balanced));
    CHECK_THROWS_WITH(LSystem::parse("F", {"{ -> F"}), Contains("the predecessor '{' cannot be rewritten"));
    CHECK_THROWS_WITH(LSystem::parse("F", {"} -> F"}), Contains("the predecessor '}' cannot be rewritten"));
    CHECK_NOTHROW(LSystem::parse("A", {"A -> [&FL!A]/////'[&FL!A]///////'[&FL!A]", "L -> ['''^^{-f+f+f-|-f+f+f}]"}));
    CHECK_NOTHROW(LSystem::parse("{[f{.f}]f}", {}));  // nested, and a bracket inside: both ABOP's
}

TEST_CASE("count_enclosed counts the symbols between braces without expanding", "[lsystem][polygon]") {
    CHECK(LSystem::parse("F{F{F}F}F", {}).count_enclosed(0, "F") == 3);
    CHECK(LSystem::parse("F{f.F}", {}).count_enclosed(0, "Ff.") == 3);
    const LSystem leaf = LSystem::parse("FXF", {"X -> {F}"});
    CHECK(leaf.count_enclosed(0, "F") == 0);
    CHECK(leaf.count_enclosed(1, "F") == 1);
    const LSystem doubled = LSystem::parse("F{F}X", {"F -> FF", "X -> F{FX}"});
    CHECK(doubled.count_enclosed(0, "F") == 1);
    // depth 1: {FF} gives 2, X -> F{FX} the F inside: 3.
    CHECK(doubled.count_enclosed(1, "F") == 3);
    // depth 2: {FFFF} gives 4, X -> FF{FF F{FX}} 2 + 1 + 1: 8.
    CHECK(doubled.count_enclosed(2, "F") == 8);
    // Against the streamed string, its brace depth tracked as it goes.
    for (int depth = 0; depth <= 6; ++depth) {
        std::uint64_t inside = 0;
        int open = 0;
        doubled.expand(depth, [&](char c, int) {
            open += c == '{' ? 1 : c == '}' ? -1 : 0;
            if (c == 'F' && open > 0) ++inside;
        });
        CHECK(doubled.count_enclosed(depth, "F") == inside);
    }
}

TEST_CASE("A depth outside 0 to max_depth is refused", "[lsystem]") {
    CHECK_THROWS_WITH(club_moss.length(-1), Catch::Contains("depth = -1 is not allowed"));
    CHECK_THROWS_AS(club_moss.counts_recursive(LSystem::max_depth + 1), std::invalid_argument);
    CHECK_THROWS_AS(club_moss.expand(-2, [](char, int) {}), std::invalid_argument);
}
