#pragma once
// A kernel's tree (sim/kernel/tree.hpp) compiled into lane programs
// (sim/kernel/lanes.hpp): types checked and conversions made as OpenCL C
// makes them, vectors taken apart into their components, every function
// inlined where it is called, every index of a buffer or array checked.

#include <cstdint>
#include <vector>

#include "sim/kernel/lanes.hpp"
#include "sim/kernel/tree.hpp"

namespace sim::kernel {

// What the caller binds to the kernel's parameters, in their order: a
// buffer it reads, one it writes, or a value.
struct Binding {
    enum class Kind { input, output, value } kind = Kind::input;
    Scalar scalar = Scalar::f32;  // the buffer's numbers, or the value's type
    std::int64_t value = 0;
};

struct Interface {
    std::string entry = "rd_compute";  // the __kernel function run
    std::vector<Binding> parameters;
    long long global[3] = {1, 1, 1};   // get_global_size
    long long trip_budget = 1 << 22;   // loop iterations a work item may take in one launch
};

// The limits of a compiled kernel: its size once every call is inlined,
// and the registers a thread keeps for it.
inline constexpr int max_operations = 1 << 20;
inline constexpr int max_registers = 8192;  // 8 MiB a thread
inline constexpr int max_masks = 1 << 16;

// Throws KernelError, naming the kernel's line.
Compiled compile(const Program& program, const Interface& interface);

}  // namespace sim::kernel
