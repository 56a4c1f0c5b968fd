#pragma once
// The passes over a lowered program (sim/formula/lower.cpp's output: SSA
// code, each register written once, in Program::code).

#include <vector>

#include "sim/formula/program.hpp"

namespace sim::formula {

// Runs of operations in `code` fused into chains (added to
// program.chains): an operation whose value only the next in the chain
// reads goes into it, and so does a short chain that is one step's operand.
std::vector<Instr> fuse_chains(Program& program, const std::vector<Instr>& code);

// Dead operations removed (program.operations: those left), chains fused,
// and registers renumbered so that buffers are shared by values whose
// lives do not overlap.
void finish_program(Program& program);

}  // namespace sim::formula
