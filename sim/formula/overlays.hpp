#pragma once
// A formula model's start, as Ready's initial pattern generator makes it:
// overlays applied in order to every cell (x fastest, then y, then z), each
// combining a fill with the chemical's value where any of its shapes holds
// the cell. Ready's definitions (its src/readybase/overlays.cpp): shapes and
// points are fractions of the grid, radii and sigmas of its largest side;
// each value is stored in the model's number type before the next overlay
// reads it. Shapes test the axes of the grid's dimensions (Ready's
// dimensionality: a rectangle on a 1-D grid is an interval of x, a circle
// on a 3-D grid a sphere). Noise comes from figgen's own seeded generator.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "sim/grid.hpp"
#include "sim/random.hpp"

namespace sim::formula {

struct Fill {
    enum class Kind { constant, white_noise, perlin_noise, linear_gradient, radial_gradient, gaussian, sine,
                      other_chemical, parameter };
    Kind kind = Kind::constant;
    double value = 0;               // constant
    double low = 0, high = 1;       // white_noise
    double scale = 64;              // perlin_noise: cells a feature
    int octaves = 8;                // perlin_noise
    double val1 = 0, val2 = 1;      // linear_gradient, radial_gradient
    double height = 1, sigma = 0.1; // gaussian
    double phase = 0, amplitude = 1;  // sine
    std::array<double, 3> p1{}, p2{};  // gradients, sine (p1, p2), gaussian (p1: centre)
    int chemical = 0;               // other_chemical
    std::string parameter;          // parameter
};

struct Shape {
    enum class Kind { everywhere, rectangle, circle, pixel };
    Kind kind = Kind::everywhere;
    std::array<double, 3> a{}, b{};  // rectangle's corners; circle's centre (a)
    double radius = 0;               // circle
    std::array<int, 3> pixel{};      // pixel
};

struct Overlay {
    enum class Operation { overwrite, add, subtract, multiply, divide };
    int chemical = 0;
    Operation operation = Operation::overwrite;
    Fill fill;
    std::vector<Shape> shapes;
};

struct Pattern {
    bool zero_first = false;  // else the overlays apply over the cells already there
    std::vector<Overlay> overlays;
};

// Each kind by the name Ready writes ("overwrite", "white_noise", "circle", ...).
std::vector<std::pair<std::string, Overlay::Operation>> operation_names();
std::vector<std::pair<std::string, Fill::Kind>> fill_names();
std::vector<std::pair<std::string, Shape::Kind>> shape_names();

// Applies `pattern` to `chemicals` (each a grid of `depth` planes of its
// rows / depth rows, the row of (y, z) z * height + y, changed in place),
// with the rule's `parameters` (for `parameter` fills), rounding each value
// to float unless `double_precision`. Throws std::invalid_argument for an
// overlay naming a chemical or parameter the rule does not have. Each cell
// is where Ready puts it, its index along each axis; `offset` (cells, x y z)
// moves them: -1/2 along an axis makes a grid of twice the resolution
// sample the places whose means are the coarser grid's cells.
void apply_pattern(const Pattern& pattern, std::vector<Grid<double>>& chemicals, int depth,
                   const std::vector<std::pair<std::string, double>>& parameters, bool double_precision, Random& rng,
                   std::array<double, 3> offset = {0, 0, 0});

// The same on a mesh's cells (Ready's MeshRD): each cell sampled at its
// centre, the mean of its points, from the mesh's least corner; the arena
// is the mesh's bounds, `extent` along each axis, and an axis of no extent
// is not tested. A pixel shape holds no cell of a mesh.
void apply_pattern_to_cells(const Pattern& pattern, std::vector<std::vector<double>>& chemicals,
                            const std::vector<std::array<double, 3>>& centres, std::array<double, 3> extent,
                            const std::vector<std::pair<std::string, double>>& parameters, bool double_precision,
                            Random& rng);

}  // namespace sim::formula
