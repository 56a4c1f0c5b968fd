#pragma once
// Formula models, as GollyGang/Ready writes them: a rule of `chemicals`
// chemicals (a, b, c, ...) on a grid of 1, 2 or 3 dimensions, each updated
// by forward Euler (or, as an option, Heun's method or RK4: Integrator),
//     X_new = X + timestep * delta_X,
// where delta_X is what the formula, a small part of OpenCL C, assigns from
// the cell's chemicals, its neighbours (a_n, a_se, a_e2, ...), Ready's
// stencils (laplacian_a, x_gradient_b, ... at three accuracies, those of
// the grid's dimensions), x_pos, y_pos and z_pos, and the rule's parameters.
//
// A formula is code from a stranger: it is read by figgen's own grammar
// into a tree (sim/formula/tree.hpp), held to fixed bounds (Limits), and
// compiled into operations over whole rows; its text never reaches a
// compiler, a shell or a shader. Only the built-in functions of an
// allow-list can be called; loops must have a trip count fixed before the
// run; arrays have a fixed size and constant indices.
//
// Ready's own behaviour is followed where it is a quirk (docs/formulas.md):
// with its default blocks of four cells in x (block_x = 4), clamped edges
// clamp per block, so that the cell west of x = 0 is x = 3; and wrapped
// edges index with `& (size - 1)`, a torus only for sizes (in blocks) that
// are powers of two.

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/formula/tree.hpp"

namespace sim::formula {

// A formula outside the grammar or its bounds: "line L, column C: what".
class FormulaError : public std::invalid_argument {
public:
    FormulaError(Pos pos, const std::string& what);
    Pos pos() const { return pos_; }
    const std::string& message() const { return message_; }  // without the position

private:
    Pos pos_;
    std::string message_;
};

// A run that cannot go on: a division by zero, or a chemical that is no
// longer a finite number. Names the step, the cell and the chemical or the
// formula's line.
class Unstable : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class Accuracy { low, medium, high };

// How a step advances the chemicals from the formula's deltas f(X):
// euler, Ready's forward Euler, X + timestep f(X) (first order); heun,
// X + timestep/2 (k1 + k2) with k1 = f(X), k2 = f(X + timestep k1) (second
// order); rk4, the classical Runge-Kutta method of fourth order. Each stage
// evaluates the whole formula, stencils and all, on the grid.
enum class Integrator { euler, heun, rk4 };
// The stages a step of each evaluates the formula: 1, 2, 4.
int stages(Integrator integrator);
// Its order in time: 1, 2, 4.
int order(Integrator integrator);
// Its name as a description gives it: "euler", "heun", "rk4".
const char* integrator_name(Integrator integrator);

// What a stencil reads past a side of the grid, where figgen's own edges
// are asked for (Rule::sides) instead of Ready's. The grid's cells are
// centred on their squares, the side half a cell past the last:
// periodic, the grid's other end (a torus of any size; both sides of an
// axis); clamped, the side's own last cell (Ready's inbuilt rules);
// neumann, zero flux, the cells mirrored about the side (the cell t past it
// reads the cell t - 1 inside), which holds the flux of every symmetric
// stencil through the side at zero and the chemicals' sum constant;
// dirichlet, the value `value` on the side, the cells mirrored about it
// (2 value - the mirrored cell), which every second-order stencil meets.
enum class Edge { periodic, clamped, neumann, dirichlet };
// Its name as a description gives it.
const char* edge_name(Edge edge);

// The grid's sides, each axis's low end then its high end: left (x = 0),
// right (x = width - 1), bottom (y = 0), top (y = height - 1, Ready's
// north), back (z = 0), front (z = depth - 1, Ready's up).
enum Side { left, right, bottom, top, back, front };
const char* side_name(int side);

struct Edges {
    struct Of {
        Edge edge = Edge::periodic;
        std::vector<double> value;  // dirichlet: one a chemical
    };
    std::array<Of, 6> side;
    // The same edge on every side (dirichlet with `value` for each chemical).
    static Edges all(Edge edge, const std::vector<double>& value = {});
};

// Chemical i's name: a, b, ..., z.
std::string chemical_name(int i);
constexpr int max_chemicals = 26;

struct Rule {
    int chemicals = 2;  // 1 .. max_chemicals
    // Names and values, in order. `timestep` is needed; `dx` is 1 unless given.
    std::vector<std::pair<std::string, double>> parameters;
    std::string code;  // the formula
    Accuracy accuracy = Accuracy::medium;
    bool wrap = true;               // a torus; else clamped edges
    int block_x = 4;                // Ready's block_size_x: 4 (its default) or 1
    bool double_precision = false;  // Ready's data type: Float64, else Float32
    // Ready's edges (its quirks above), as its own patterns need; else a
    // true torus of any size, or each cell clamped to the grid.
    bool ready_edges = true;
    // figgen's own edges, side by side (Edges); given, they replace `wrap`
    // and `ready_edges`. The sides of an axis the grid does not have (one
    // cell along it) read the cell itself, whatever they say.
    std::optional<Edges> edges;
    // The edges figgen computes where ready_edges is false: `edges`, or
    // else every side periodic (wrap) or clamped.
    Edges own_edges() const;
    // Ready's OpenCL arithmetic: pocl's clang contracts a * b + c (and
    // a * b - c, c - a * b) inside one expression into a fused multiply-add
    // (OpenCL C's FP_CONTRACT ON), so that it rounds once; else every
    // operation rounds on its own.
    bool fused_multiply_add = false;
    Integrator integrator = Integrator::euler;

    // Throws std::invalid_argument naming what is wrong, FormulaError for
    // the code, before anything runs.
    void validate(int width, int height, int depth = 1) const;
    // The value of parameter `name` (its last), or `fallback` where there is none.
    double parameter(const std::string& name, double fallback = 0) const;
    // Sets parameter `name` (its last, or a new one) to `value`.
    void set_parameter(const std::string& name, double value);
};

// A parameter's value as the formula reads it: Ready holds parameters as
// float and writes them into its kernel with 8 decimals, so that in a
// double rule 1.1 is 1.10000002 and a timestep of 0.3 is 0.30000001.
double formula_value(double parameter);

// The most cells a grid holds, in any number of dimensions (16384^2).
constexpr long long max_cells = 16384LL * 16384LL;

// A grid's dimensions as Ready counts them: its sides longer than one cell
// (a 256 x 1 x 1 grid is 1-D, 32 x 32 x 32 is 3-D). Ready's stencils and
// gradient_mag_squared follow it; a grid of one cell counts as 1-D.
int dimensionality(int width, int height, int depth);

// Whether `name` is one of the formula language's built-in functions of
// numbers (the relational ones, isless ..., aside): sim/formula/builtins.cpp.
bool is_builtin_function(const std::string& name);

}  // namespace sim::formula
