// The fusion pass: runs of operations into chains (sim/formula/program.hpp's
// Chain), each evaluated in one pass over a chunk of cells.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "sim/formula/passes.hpp"

namespace sim::formula {

namespace {

// Whether instruction `in` may go into a chain: nothing in it can fail.
bool chainable(const Instr& in, const std::vector<char>& is_constant, const std::vector<double>& value) {
    switch (in.op) {
    case Op::stencil: return true;
    case Op::add:
    case Op::sub:
    case Op::mul: return in.a >= 0 && in.b >= 0;
    case Op::div: return in.a >= 0 && in.b >= 0 && is_constant[in.b] && value[in.b] != 0 && !is_constant[in.a];
    case Op::fma: return in.a >= 0 && in.b >= 0 && in.c >= 0;
    default: return false;
    }
}

}  // namespace

// The SSA code `code` (each register written once) with runs of
// operations fused into chains: an operation whose value only the next
// in the chain reads goes into it, and so does a short chain that is
// one step's operand (as the second accumulator).
std::vector<Instr> fuse_chains(Program& program, const std::vector<Instr>& code) {
    const int n = program.registers;
    const int count = static_cast<int>(code.size());
    std::vector<char> is_constant(static_cast<std::size_t>(n), 0);
    std::vector<double> value(static_cast<std::size_t>(n), 0);
    for (const Program::Constant& c : program.constants) {
        is_constant[c.reg] = 1;
        value[c.reg] = c.value;
    }
    std::vector<int> def(static_cast<std::size_t>(n), -1), uses(static_cast<std::size_t>(n), 0);
    for (int i = 0; i < count; ++i) {
        def[code[i].dst] = i;
        for (int r : sources(program, code[i])) ++uses[r];
    }
    for (int out : program.outputs) ++uses[out];
    std::vector<char> can(static_cast<std::size_t>(count), 0);
    for (int i = 0; i < count; ++i) can[i] = chainable(code[i], is_constant, value);
    // through[i]: the operand (a or b) whose chain instruction i
    // continues, or -1; length[i]: the chain's operations up to i.
    std::vector<int> through(static_cast<std::size_t>(count), -1), length(static_cast<std::size_t>(count), 1);
    std::vector<char> interior(static_cast<std::size_t>(count), 0);
    // The operands of an instruction a chain may continue through: a and b,
    // and an fma's c; one that appears twice never.
    auto operands = [&](const Instr& in) {
        std::vector<int> regs{in.a, in.b};
        if (in.op == Op::fma) regs.push_back(in.c);
        std::vector<int> once;
        for (int r : regs)
            if (std::count(regs.begin(), regs.end(), r) == 1) once.push_back(r);
        return once;
    };
    for (int i = 0; i < count; ++i) {
        const Instr& in = code[i];
        if (!can[i] || in.op == Op::stencil || (in.op != Op::fma && in.a == in.b)) continue;
        int best = -1;
        for (int r : operands(in)) {
            if (in.op == Op::div && r != in.a) continue;  // the divisor is the constant
            const int d = def[r];
            if (d < 0 || !can[d] || uses[r] != 1 || interior[d]) continue;
            if (best < 0 || length[d] > length[def[best]]) best = r;
        }
        if (best < 0) {
            can[i] = in.op != Op::fma;  // an fma only continues a chain, never starts one
            continue;
        }
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
    // An fma's two operands besides the one it continues through, in order.
    auto others = [&](int i) {
        const Instr& in = code[i];
        std::vector<int> rest;
        for (int r : {in.a, in.b, in.c})
            if (r != through[i]) rest.push_back(r);
        return rest;
    };
    // Short chains taken whole as one step's operand.
    constexpr int aux_most = 4;  // operations of such a chain
    std::vector<char> absorbed(static_cast<std::size_t>(count), 0), has_aux(static_cast<std::size_t>(count), 0);
    std::vector<char> has_stencil(static_cast<std::size_t>(count), 0), has_fma(static_cast<std::size_t>(count), 0);
    for (int i = 0; i < count; ++i) {
        has_stencil[i] = code[i].op == Op::stencil || (through[i] >= 0 && has_stencil[def[through[i]]]);
        has_fma[i] = code[i].op == Op::fma || (through[i] >= 0 && has_fma[def[through[i]]]);
    }
    for (int root = 0; root < count; ++root) {
        if (!can[root] || interior[root]) continue;
        for (int link : path(root)) {
            if (through[link] < 0) continue;
            // One operand of each link at most (an fma's first that can).
            for (int o : code[link].op == Op::fma ? others(link) : std::vector<int>{other(link)}) {
                const int d = def[o];
                if (d < 0 || !can[d] || interior[d] || absorbed[d] || uses[o] != 1 || has_stencil[d] || has_aux[d] ||
                    has_fma[d] || length[d] > aux_most)
                    continue;
                absorbed[d] = 1;
                has_aux[root] = 1;
                break;
            }
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
        // An fma with the value so far: the operand from an absorbed chain
        // (if any) into aux first, the rest as rows or constants.
        auto fma_link = [&](int i) {
            const Instr& in = code[i];
            Chain::Step st;
            st.kind = Chain::Kind::fma;
            st.op = Op::fma;
            st.signs = in.signs;
            const int regs[3] = {in.a, in.b, in.c};
            for (int s = 0; s < 3; ++s)
                if (regs[s] == through[i]) st.slot = s;
            for (int s = 0; s < 3 && st.aux_slot < 0; ++s) {
                if (s == st.slot) continue;
                const int d = def[regs[s]];
                if (d < 0 || !absorbed[d]) continue;
                const std::vector<int> side = path(d);
                head(side.front(), true);
                for (std::size_t q = 1; q < side.size(); ++q) link(side[q], Chain::Kind::aux_op);
                st.aux_slot = s;
            }
            bool first = true;
            for (int s = 0; s < 3; ++s) {
                if (s == st.slot || s == st.aux_slot) continue;
                if (first) operand(regs[s], st.x, st.kx);
                else operand(regs[s], st.y, st.ky);
                first = false;
            }
            chain.steps.push_back(st);
        };
        head(steps.front(), false);
        for (std::size_t k = 1; k < steps.size(); ++k) {
            const int i = steps[k];
            if (code[i].op == Op::fma) {
                fma_link(i);
                continue;
            }
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
        in.a = static_cast<int>(program.chains.size());
        in.b = in.c = in.mask = -1;
        program.chains.push_back(std::move(chain));
        fused.push_back(in);
    }
    return fused;
}


}  // namespace sim::formula
