#pragma once
// A compiled kernel: straight-line operations over registers of `lanes`
// work items at once, with structured control flow as masks of those
// lanes (sim/kernel/compile.cpp makes it; sim/kernel/exec.cpp runs it).
//
// Every register holds one scalar a lane (a vector is one register a
// component) and a flag: uniform when every lane holds the same value,
// kept in lane 0 alone. Loop counters, constants and what is computed from
// them stay uniform, so they are computed once for a chunk of work items.
// A branch's lanes are a mask; straight-line operations compute every
// lane, and only what can fail (a division by zero, a buffer's or array's
// index) or what stays (an assignment, a store) looks at the mask.

#include <cstdint>
#include <string>
#include <vector>

#include "sim/kernel/tree.hpp"

namespace sim::kernel {

constexpr int lanes = 128;

struct Ctx;
struct Op;
using OpFn = void (*)(Ctx&, const Op&);

// One operation: fn reads registers a, b, c and writes dst; what the
// others mean is fn's.
struct Op {
    OpFn fn = nullptr;
    int dst = -1, a = -1, b = -1, c = -1;
    int line = 0;
    int aux = 0;
    std::int64_t i = 0;
    double f = 0;
};

struct Block {
    std::vector<Op> ops;
};

// A buffer the kernel reads or writes: a chemical's cells, as elements of
// `width` numbers (a float4 buffer: four).
struct BufferView {
    std::string name;  // the parameter's name, for messages
    int parameter = 0;  // its place in the kernel's parameters
    bool output = false;
    Scalar scalar = Scalar::f32;
    int width = 1;
};

// Arrays (a function's own, or program-scope constants): `count`
// elements of `width` registers from `base`, in dimensions `dims`.
struct ArrayInfo {
    std::string name;
    int base = 0, width = 1;
    long long count = 0;
    std::vector<long long> dims;
};

struct IfNode {
    int cond, then_block, else_block;  // else_block -1: none
    int then_mask, else_mask, join;
};

struct LoopNode {
    int cond_block, cond;  // cond -1: always true (the block may still compute)
    int body, step;
    bool test_first;       // false: do-while
    int lm, exit, broken, continued;
};

struct SwitchNode {
    int selector;  // an i64 register
    struct Segment {
        std::vector<std::int64_t> labels;
        bool is_default = false;
        bool has_body = false;
        int block;
    };
    std::vector<Segment> segments;
    int entry, enter, fall, broken;
};

// c ? x : y, && and ||: sub-blocks run under a narrower mask.
struct GuardNode {
    int cond;             // mask register
    int first, second;    // blocks (-1: none)
    int saved, first_mask, second_mask;
    bool negate;          // ||: the second runs where cond is false
};

// An inlined call: its body runs under the mask; lanes that return are
// kept aside until it ends.
struct CallNode {
    int body, returned, join;
};

struct Compiled {
    std::vector<Block> blocks;  // blocks[0]: the program-scope constants; blocks[1]: the kernel
    std::vector<IfNode> ifs;
    std::vector<LoopNode> loops;
    std::vector<SwitchNode> switches;
    std::vector<GuardNode> guards;
    std::vector<CallNode> calls;
    std::vector<ArrayInfo> arrays;
    std::vector<BufferView> buffers;
    int registers = 0;     // value registers
    int masks = 0;         // mask registers (0: always empty; 1: the chunk's lanes)
    int id_registers[3] = {0, 0, 0};  // get_global_id(0..2), u64
    long long global[3] = {1, 1, 1};  // get_global_size
    long long trip_budget = 0;        // loop iterations a work item may take a step
    int operations = 0;               // straight-line operations in all blocks
};

// Where a run failed: the kernel's line and the work item; the message
// without the step, which the caller adds.
struct Failure {
    bool failed = false;
    long long item = 0;
    int line = 0;
    std::string what;
};

// The buffers of one launch: input and output elements of each view, as
// bytes of floats or doubles, and the writes' stamps of the outputs.
struct Launch {
    std::vector<const void*> data;       // per buffer view
    std::vector<void*> out;              // per buffer view (null for inputs)
    std::vector<long long> elements;     // per buffer view
    std::vector<std::int32_t*> stamps;   // per buffer view (outputs): the work item that wrote each element, -1 none
};

// Runs work items [first, first + count) of `program` (count <= lanes).
// Returns false, filling `failure`, at the first failure.
class Lanes {
public:
    explicit Lanes(const Compiled& program);
    ~Lanes();
    Lanes(const Lanes&) = delete;
    Lanes& operator=(const Lanes&) = delete;
    bool run(const Launch& launch, long long first, int count, Failure& failure);
    // Operations run so far, each over one chunk's lanes: the work a step
    // took, counted the same on every machine.
    long long executed() const;

private:
    Ctx* ctx_;
};

}  // namespace sim::kernel
