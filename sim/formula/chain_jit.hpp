#pragma once
// A chain of a compiled formula as machine code (sim/formula/chain_jit.cpp):
// its Plan (sim/formula/chain_kernels.hpp) written out as x86-64 AVX2
// instructions with Xbyak, one run of instructions per operation, in the
// Plan's order, on the same registers (acc, aux and g, four vectors each),
// with nothing between them: the threaded code's jump from one operation
// to the next, and the load of its row and constant, are gone. Each
// operation rounds as the vector code's does, so the bits are the same.
//
// The code is made from the Plan, which figgen made from the checked tree:
// no text of the formula reaches it, and it reads only the rows the Plan
// names, at the lanes the caller gives.

#include <cstddef>
#include <memory>

namespace sim::formula::fused {

template <class Real>
struct Plan;

class ChainCode {
public:
    virtual ~ChainCode() = default;
    // Lanes from .. n - 1 in whole vectors: returns the first lane not done
    // (fewer than a vector's width remain); bad: whether a lane done is not
    // finite (with check).
    virtual int run(const void* const* view, void* d, int from, int n, bool check, bool& bad) const = 0;
};

// Whether this build and processor make machine code (x86-64 with AVX2 and
// FMA), and whether chains use it now (the default where it can).
bool jit_available();
bool jit_in_use();
void use_jit(bool on);  // on: only where jit_available()

// The bytes of machine code a plan of `operations` operations is given:
// an operation on four vectors and again on one is at most about 200.
constexpr std::size_t code_bytes(std::size_t operations) {
    return 4096 + operations * 320;
}

// The machine code of a plan; null where there is none (not available, or
// Xbyak refused).
std::shared_ptr<const ChainCode> compile_chain(const Plan<float>& plan);
std::shared_ptr<const ChainCode> compile_chain(const Plan<double>& plan);

}  // namespace sim::formula::fused
