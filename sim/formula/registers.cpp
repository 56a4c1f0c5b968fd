// The last passes: dead operations removed, chains fused
// (sim/formula/fuse.cpp), and registers renumbered and shared.

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <vector>

#include "sim/formula/passes.hpp"

namespace sim::formula {

// Dead operations removed; registers renumbered so that buffers are
// shared by values whose lives do not overlap.
void finish_program(Program& program) {
    const int n = program.registers;
    std::vector<char> live(static_cast<std::size_t>(n), 0);
    for (int out : program.outputs) live[out] = 1;
    std::vector<char> keep(program.code.size(), 0);
    for (int i = static_cast<int>(program.code.size()) - 1; i >= 0; --i) {
        const Instr& in = program.code[i];
        if (!live[in.dst]) continue;
        keep[i] = 1;
        for (int r : sources(program, in)) live[r] = 1;
    }
    std::vector<Instr> code;
    for (std::size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) code.push_back(program.code[i]);
    program.operations = static_cast<int>(code.size());
    code = fuse_chains(program, code);
    std::fill(live.begin(), live.end(), 0);
    for (int out : program.outputs) live[out] = 1;
    for (const Instr& in : code)
        for (int r : sources(program, in)) live[r] = 1;
    // Register kinds: inputs and the positions are views; constants filled once.
    std::vector<char> temporary(static_cast<std::size_t>(n), 1);
    for (const Program::Input& in : program.inputs) temporary[in.reg] = 0;
    for (const Program::Constant& c : program.constants) temporary[c.reg] = 0;
    for (int pos : {program.x_pos, program.y_pos, program.z_pos})
        if (pos >= 0) temporary[pos] = 0;
    for (int out : program.outputs) temporary[out] = 0;
    std::vector<int> map(static_cast<std::size_t>(n), -1);
    int next = 0;
    std::vector<Program::Input> inputs;
    for (const Program::Input& in : program.inputs)
        if (live[in.reg]) {
            map[in.reg] = next++;
            inputs.push_back({map[in.reg], in.chemical, in.dx, in.dy, in.dz});
        }
    // radius from the inputs kept
    program.radius_x = program.radius_y = program.radius_z = 0;
    for (const Program::Input& in : inputs) {
        program.radius_x = std::max(program.radius_x, std::abs(in.dx));
        program.radius_y = std::max(program.radius_y, std::abs(in.dy));
        program.radius_z = std::max(program.radius_z, std::abs(in.dz));
    }
    for (int* pos : {&program.x_pos, &program.y_pos, &program.z_pos})
        if (*pos >= 0) *pos = live[*pos] ? (map[*pos] = next++) : -1;
    std::vector<Program::Constant> constants;
    for (const Program::Constant& c : program.constants)
        if (live[c.reg]) {
            map[c.reg] = next++;
            constants.push_back({map[c.reg], c.value});
        }
    // Temporaries: a buffer freed after its last use is taken again.
    std::vector<int> last_use(static_cast<std::size_t>(n), -1);
    for (int i = 0; i < static_cast<int>(code.size()); ++i)
        for (int r : sources(program, code[i])) last_use[r] = i;
    for (int out : program.outputs) last_use[out] = static_cast<int>(code.size());
    std::vector<int> free_buffers;
    std::vector<StencilSum> stencils;
    for (int i = 0; i < static_cast<int>(code.size()); ++i) {
        Instr& in = code[i];
        const std::vector<int> read = sources(program, in);
        // Renumbered: the operands, a chain's operands and its stencils' inputs (in their own copies).
        if (in.op == Op::chain) {
            for (Chain::Step& st : program.chains[in.a].steps) {
                for (int* r : {&st.x, &st.y})
                    if (*r >= 0) *r = map[*r];
                if (st.stencil >= 0) {
                    StencilSum sum = program.stencils[st.stencil];
                    for (StencilSum::Term& t : sum.terms)
                        for (int& r : t.inputs) r = map[r];
                    st.stencil = static_cast<int>(stencils.size());
                    stencils.push_back(std::move(sum));
                }
            }
        } else {
            for (int* r : {&in.a, &in.b, &in.c, &in.mask})
                if (*r >= 0) *r = map[*r];
        }
        for (int virt : read)
            if (last_use[virt] == i && temporary[virt]) {
                free_buffers.push_back(map[virt]);
                last_use[virt] = -2;  // freed once
            }
        if (map[in.dst] < 0) {
            if (!free_buffers.empty()) {
                map[in.dst] = free_buffers.back();
                free_buffers.pop_back();
            } else {
                map[in.dst] = next++;
            }
        }
        in.dst = map[in.dst];
    }
    for (int& out : program.outputs) out = map[out];
    program.code = std::move(code);
    program.stencils = std::move(stencils);
    program.inputs = std::move(inputs);
    program.constants = std::move(constants);
    program.registers = next;
}

}  // namespace sim::formula
