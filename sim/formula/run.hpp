#pragma once
// A formula rule's run (sim/formula/run.cpp): the rule compiled into row
// operations (sim/formula/program.hpp) and stepped over its grid.

#include <memory>
#include <vector>

#include "sim/formula/rule.hpp"
#include "sim/grid.hpp"

namespace sim::formula {

// The most cells a run's register holds at once (a chunk of a row, or of
// several rows with their halos): each thread has the compiled formula's
// registers of this many cells, and a cache line more.
constexpr int chunk_lanes = 2048;

// The copies of each chemical's rows a run keeps at most: forward Euler
// three on a 2-D grid (its steps go in blocks, sim/formula/run.cpp), else
// two; Heun three, RK4 four (the state, the new state, the stages').
constexpr int state_copies(int height, int depth, Integrator integrator = Integrator::euler) {
    if (integrator == Integrator::rk4) return 4;
    if (integrator == Integrator::heun) return 3;
    return depth == 1 && height > 1 ? 3 : 2;
}

// Whether a 2-D run may take its steps in blocks (on unless the tests
// compare it with one step at a time; the same bits either way).
void use_temporal_blocking(bool on);

// A run of a rule on a width x height x depth grid. A chemical's cells are
// a Grid of height * depth rows: the row of (y, z) is z * height + y, its
// column x.
class Run {
public:
    // Compiles the rule (FormulaError, std::invalid_argument) for the
    // grid's dimensions (dimensionality()) and loads the start: one grid
    // per chemical, rounded to the rule's number type.
    Run(const Rule& rule, int width, int height, int depth, const std::vector<Grid<double>>& start);
    // A 2-D (or 1-D: height 1) grid.
    Run(const Rule& rule, int width, int height, const std::vector<Grid<double>>& start)
        : Run(rule, width, height, 1, start) {}
    ~Run();
    Run(Run&&) noexcept;
    Run& operator=(Run&&) noexcept;

    // `steps` steps on `threads` threads (0: OpenMP's default); the same
    // bits for any number. Throws Unstable at the first step that fails
    // (the state is then that step's input).
    void step(int steps, int threads = 0);
    Grid<double> chemical(int i) const;
    long long steps() const;
    int width() const;
    int height() const;
    int depth() const;
    // Row operations a cell of one step takes: the compiled formula's size.
    int operations() const;
    // The steps a block of its steps takes (1: one at a time).
    int block_steps() const;

    struct Impl;  // the engine of the rule's number type (sim/formula/run.cpp)

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace sim::formula
