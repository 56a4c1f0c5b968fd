#pragma once
// Bracketed, context-free, deterministic L-systems (Prusinkiewicz &
// Lindenmayer, The Algorithmic Beauty of Plants, ch. 1). The depth-n string
// grows exponentially (the club moss has 3 * 6^n - 2 symbols), so it is never
// built: length() and counts() count it by dynamic programming on symbol
// counts, and expand() streams it symbol by symbol from a stack of frames.
//
// Two readings of "depth n":
//  - rewrite (expand): the usual one, every symbol with a rule is rewritten
//    n times, in parallel, then the string is read.
//  - article (expand_recursive): the turtle code of the club moss article
//    (seeds/001), a recursive interpretation:
//        f(n):    if n > 0: L(rule_F, n)
//        L(s, n): for c in s: ... 'F': f(n - 1); fd(d)
//    Each F of a successor at level n is replaced by the expansion of its
//    rule at level n - 1 followed by the F itself, drawn at level n with the
//    fixed length d. Generalised to any symbol c with a rule:
//        R(s, n) = concat over c in s of  (c has a rule and n > 1) ? R(rule_c, n-1) c : c
//    for n >= 1: at n = 1 a symbol stays bare, as f(0) draws nothing. The
//    axiom is read as f: its symbols with a rule become R(rule_c, depth)
//    (nothing at depth 0), the others are kept.
//    (The article's Python widths differ from its evident intent: ']' calls
//    pensize(p) with p = n, not 2 n, and after f(n - 1) returns the pen keeps
//    the width set inside it. The turtle uses the intent, 2 * level.)
//    For F -> FF+[+F-F]-[-F+F] (16 symbols, 6 F) and axiom F, the string has
//        F count       A(n) = 6 (A(n-1) + 1), A(0) = 0:  A(n) = 6 (6^n - 1) / 5
//        symbol count  S(n) = 16 + 6 S(n-1), S(0) = 0:   S(n) = 16 (6^n - 1) / 5
//    against the rewrite reading's 6^n F in 3 * 6^n - 2 symbols.
//
// The level passed with each streamed symbol is the level of the frame that
// wrote it, the article's n. Rewrite: the axiom's frame is level `depth`, a
// successor expanded from a level-k frame is level k - 1, so a symbol that
// still has a rule is only emitted at level 0. Article: the axiom's rules
// expand at level `depth` (f(depth) calls L(rule, depth)), a successor
// expanded for a symbol of a level-k frame is level k - 1, and the symbol
// drawn after it stays at level k: the article's pensize(2 k), thick trunk,
// thin tips at level 1.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sim {

// Symbols a rule or axiom may use: letters, the turtle's turns + - & ^ \ / |,
// the brackets [ ], ! (width decay), and ABOP's polygon and colour symbols
// { } . ' (sim/turtle.hpp). Brackets and braces are balanced in the axiom
// and in every successor, and neither may be rewritten.
bool lsystem_symbol(char c);

struct LSystem {
    std::string axiom;                  // the depth-0 string; never empty, brackets balanced
    std::map<char, std::string> rules;  // X -> successor; symbols without a rule are copied

    // Rules read "F -> FF+[+F-F]-[-F+F]" or "F=FF+..." (spaces ignored).
    // Throws std::invalid_argument, one line naming the rule and the
    // problem: missing arrow, predecessor not one symbol, duplicate
    // predecessor, unbalanced brackets, unknown symbol, empty axiom.
    static LSystem parse(std::string_view axiom, const std::vector<std::string>& rules);

    void validate() const;  // the checks of parse() on a hand-built system

    // Rewrite reading. Counts saturate at UINT64_MAX. depth 0..max_depth.
    std::uint64_t length(int depth) const;                  // symbols in the depth-n string
    std::map<char, std::uint64_t> counts(int depth) const;  // occurrences of each symbol in it
    // Article reading, the same for the string expand_recursive() streams.
    std::uint64_t length_recursive(int depth) const;
    std::map<char, std::uint64_t> counts_recursive(int depth) const;
    // Rewrite reading: how many of `symbols` stand inside a pair of braces
    // { } in the depth-n string (a polygon's vertex moves), counted without
    // expanding. Saturates like counts().
    std::uint64_t count_enclosed(int depth, std::string_view symbols) const;

    // Streams the depth-n string to visit(char symbol, int level). Memory is
    // O(depth): each frame is a view of the axiom or of a rule.
    template <class Visit>
    void expand(int depth, Visit&& visit) const {
        walk(depth, false, visit);
    }
    template <class Visit>
    void expand_recursive(int depth, Visit&& visit) const {
        walk(depth, true, visit);
    }

    static constexpr int max_depth = 4096;  // far past any drawable depth; bounds the counting loops

private:
    struct Frame {
        std::string_view text;  // the axiom or a successor
        std::size_t pos;        // next symbol of text to read
        int level;              // the frame's level, see above
        bool emit_on_return;    // article reading: the parent emits its symbol when this frame ends
    };
    using Successors = std::array<const std::string*, 256>;  // by unsigned char; nullptr: no rule
    Successors successor_table() const;
    void check_depth(int depth) const;

    template <class Visit>
    void walk(int depth, bool article, Visit& visit) const {
        check_depth(depth);
        const Successors next = successor_table();
        auto rule_of = [&](char c) { return next[static_cast<unsigned char>(c)]; };
        std::vector<Frame> stack;
        stack.reserve(static_cast<std::size_t>(depth) + 1);
        stack.push_back({axiom, 0, depth, false});
        while (!stack.empty()) {
            Frame& top = stack.back();
            if (top.pos == top.text.size()) {
                const bool emit = top.emit_on_return;
                stack.pop_back();
                if (emit) {  // the article's fd(d) after f(n - 1)
                    Frame& parent = stack.back();
                    visit(parent.text[parent.pos], parent.level);
                    ++parent.pos;
                }
                continue;
            }
            const char c = top.text[top.pos];
            const std::string* successor = rule_of(c);
            const bool axiom_frame = stack.size() == 1;
            if (!successor) {
                visit(c, top.level);
                ++top.pos;
            } else if (!article) {
                ++top.pos;
                if (top.level > 0)
                    stack.push_back({*successor, 0, top.level - 1, false});
                else
                    visit(c, 0);
            } else if (axiom_frame) {  // f(depth): the rule's expansion replaces c
                ++top.pos;
                if (top.level > 0) stack.push_back({*successor, 0, top.level, false});
            } else if (top.level > 1) {  // f(n - 1) first, then c at this level on return
                stack.push_back({*successor, 0, top.level - 1, true});
            } else {  // f(0) draws nothing: only c itself
                visit(c, top.level);
                ++top.pos;
            }
        }
    }
};

}  // namespace sim
