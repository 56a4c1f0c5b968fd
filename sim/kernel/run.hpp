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

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
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

// What a kernel's parameters after its 2 x chemicals buffers are bound to:
// a buffer of ints or floats it reads (a mesh's neighbour indices and
// weights), or an int value (max_neighbors).
struct Extra {
    enum class Kind { ints, floats, value } kind = Kind::value;
    std::vector<std::int32_t> ints;
    std::vector<float> floats;
    std::int64_t value = 0;
};

// A kernel run over `cells` numbers a chemical, launched over `global`
// work items a step: the engine of ImageRun and MeshRun.
class KernelRun {
public:
    KernelRun(const std::string& text, int chemicals, bool float64, long long cells, const long long global[3],
              std::vector<Extra> extras, const std::vector<std::vector<double>>& start, long long trip_budget);
    ~KernelRun();
    KernelRun(KernelRun&&) noexcept;
    KernelRun& operator=(KernelRun&&) noexcept;
    void step(int steps, int threads = 0);
    std::vector<double> values(int chemical) const;
    long long steps() const;
    int operations() const;
    // How a cell is named in messages ("cell 12" unless given).
    void name_cells(std::function<std::string(long long)> name);
    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

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

private:
    int width_ = 0, height_ = 0, depth_ = 0;
    std::unique_ptr<KernelRun> run_;
};

// A kernel rule or a formula rule on a mesh, as Ready's
// FullKernelOpenCLMeshRD and FormulaOpenCLMeshRD run them: one work item
// a cell, the kernel's parameters a_in, b_in, ..., a_out, b_out, ...,
// then the neighbour indices (int*), their weights (float*) and
// max_neighbors (int).
struct MeshRule {
    std::string text;      // the kernel (mesh_formula_kernel makes a formula's)
    int chemicals = 1;
    bool float64 = false;
    long long trip_budget = 1 << 22;
};

// The kernel Ready writes for a formula rule on a mesh
// (FormulaOpenCLMeshRD::AssembleKernelSourceFromFormula): each chemical
// read, its Laplacian summed over the neighbour list (-x + sum of x_j w_j,
// times 4), the parameters as constants with 6 decimals, the formula, and
// forward Euler with `timestep`. The formula is spliced in as Ready does;
// the whole is then read by figgen's own grammar like any kernel.
std::string mesh_formula_kernel(const std::string& formula, int chemicals, bool float64,
                                const std::vector<std::pair<std::string, double>>& parameters);

class MeshRun {
public:
    // `neighbours`: cells x max_neighbors indices and weights
    // (sim/mesh/mesh.hpp's Neighbours, as plain arrays).
    MeshRun(const MeshRule& rule, long long cells, int max_neighbors, const std::vector<int>& indices,
            const std::vector<float>& weights, const std::vector<std::vector<double>>& start);
    void step(int steps, int threads = 0) { run_->step(steps, threads); }
    std::vector<double> chemical(int i) const { return run_->values(i); }
    long long steps() const { return run_->steps(); }
    int operations() const { return run_->operations(); }

private:
    std::unique_ptr<KernelRun> run_;
};

// The operations of `rule`'s kernel compiled for a mesh of `cells` cells
// (a MeshRun's operations()), without its buffers: KernelError for a
// kernel figgen cannot run, before anything runs.
int mesh_kernel_operations(const MeshRule& rule, long long cells, int max_neighbors);

// Bytes a mesh run keeps: two buffers a chemical, the stamps, the
// neighbour lists.
long long mesh_run_bytes(const MeshRule& rule, long long cells, int max_neighbors);

}  // namespace sim::kernel
