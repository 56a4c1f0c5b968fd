#pragma once
// A kernel rule run as Ready's FullKernelOpenCLImageRD runs it, with no
// OpenCL: the kernel called once a step over a 3-D range of work items,
// one a block of cells (width / block_x, height / block_y, depth /
// block_z, each at least 1), its parameters a_in, b_in, ... then a_out,
// b_out, ... bound by position to two buffers a chemical that swap after
// every step. An output a step does not write keeps what its buffer held
// two steps before (the second buffer starts at zero).
//
// figgen's own compiler (sim/kernel/compile.hpp) runs the kernel over
// chunks of work items at once (sim/kernel/lanes.hpp), the chunks on
// threads; each work item reads only the inputs and its own writes, and
// each output element is written by one work item, so the bits are the
// same on any number of threads. A work item that writes an element
// another wrote in the same step, or reads an output it did not write,
// stops the run, as does an index outside a buffer or array, an integer
// division by zero, too many loop iterations, and a number that is no
// longer finite.

#include <memory>
#include <string>
#include <vector>

#include "sim/grid.hpp"
#include "sim/kernel/tree.hpp"

namespace sim::kernel {

struct ImageRule {
    std::string text;        // the kernel, as the pattern file holds it
    int chemicals = 1;
    bool float64 = false;    // the chemicals' numbers: double, else float
    int block[3] = {1, 1, 1};
    long long trip_budget = 1 << 22;
};

// The most cells of a kernel run: a work item's number is an int.
inline constexpr long long max_kernel_cells = (1LL << 31) - 1;

// Bytes a run keeps besides its threads' registers: two buffers a
// chemical and the writes' stamps.
long long run_bytes(const ImageRule& rule, long long cells);
// Bytes each thread keeps for the compiled kernel's registers.
long long thread_bytes(const ImageRule& rule, int width, int height, int depth);

class ImageRun {
public:
    // Compiles the kernel (KernelError naming its line) for the grid and
    // loads the start: one grid a chemical of `height * depth` rows of
    // `width`, rounded to the rule's numbers.
    ImageRun(const ImageRule& rule, int width, int height, int depth, const std::vector<Grid<double>>& start);
    ~ImageRun();
    ImageRun(ImageRun&&) noexcept;
    ImageRun& operator=(ImageRun&&) noexcept;

    // `steps` launches on `threads` threads (0: OpenMP's default). Throws
    // KernelError naming the step, the work item and the kernel's line;
    // the state is then the failed step's input.
    void step(int steps, int threads = 0);
    Grid<double> chemical(int i) const;
    long long steps() const;
    // Operations of the compiled kernel, all calls inlined.
    int operations() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace sim::kernel
