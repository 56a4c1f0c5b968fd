#pragma once
// Ready's meshes (its MeshRD): cells of VTK's kinds over points in space,
// each cell holding the chemicals, and the cells each one's Laplacian
// reads: Ready's neighbour lists, in Ready's order and with its weights,
// computed as Ready computes them through VTK 9.1 but without VTK. The
// order decides how a Laplacian's sum rounds, so it is Ready's exactly
// (checked against VTK itself, tests/sim/mesh/ready_neighbours.py).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sim::mesh {

// VTK's numbers for the cell types figgen reads (vtkCellType.h).
namespace cell_type {
inline constexpr std::uint8_t triangle = 5, polygon = 7, quad = 9, tetra = 10, voxel = 11, hexahedron = 12,
                              wedge = 13, pyramid = 14, polyhedron = 42;
}

// Cells over points, as vtkUnstructuredGrid holds them.
struct Mesh {
    std::vector<double> points;              // x, y, z of each point
    std::vector<std::int64_t> offsets{0};    // cell c's points: point_ids[offsets[c] .. offsets[c + 1])
    std::vector<std::int64_t> point_ids;     // VTK's connectivity
    std::vector<std::uint8_t> types;         // each cell's VTK type
    // A polyhedron's faces, as VTK's XML holds them: for each polyhedron in
    // turn its face count, then each face's point count and points. Both
    // empty when no cell is a polyhedron; else face_offsets has one a cell:
    // where its faces end in `faces`, -1 for a cell that is not a polyhedron.
    std::vector<std::int64_t> faces, face_offsets;

    std::size_t point_count() const { return points.size() / 3; }
    std::size_t cell_count() const { return types.size(); }
};

// The most points of one cell, and of one polyhedron's face, figgen reads.
inline constexpr std::int64_t max_cell_points = 64;
// The most faces of one polyhedron.
inline constexpr std::int64_t max_cell_faces = 256;

// Throws std::invalid_argument, naming the cell, when the mesh is not one
// VTK would hold: arrays of unlike lengths, offsets that do not rise from
// 0 to point_ids' end, a point index outside the points, a type figgen does
// not read or a cell with the wrong number of points for it, a
// polyhedron's faces that do not match face_offsets or name a point not
// among its own, or points not finite.
void check(const Mesh& mesh);

// Which cells are a cell's neighbours (Ready's neighborhood_type).
enum class Kind { vertex, edge, face };

// Ready's neighbour lists (MeshRD::ComputeCellNeighbors): for each cell,
// max_neighbors slots of (cell index, weight), the neighbours first, each
// weighted 1.0f / N as float (N: the cell's neighbours), then padding, the
// cell itself weighted 0.0f. max_neighbors is the longest list, at least 1
// (0 for a mesh of no cells).
struct Neighbours {
    int max_neighbors = 0;
    std::vector<int> indices;     // cells x max_neighbors
    std::vector<float> weights;   // cells x max_neighbors
};

// Ready's neighbours of each cell, in Ready's order:
//   face: the cells sharing each face of the cell (none for 2-D cells),
//   edge: the cells sharing each edge of the cell,
//         faces and edges in VTK's order for the cell's type, and for each
//         one the cells in increasing index, each cell where it first comes;
//   vertex: the cells sharing a point, in a ring: the first one found, then
//         over and over the cell's points in order, each point's cells in
//         increasing index, a cell added when it shares an edge with the
//         last one added; then whatever is left, as found.
// Throws std::invalid_argument for a mesh check() refuses, one of more than
// one cell type (Ready refuses those), or one whose cells share their points
// with so many others that the search would pass max_neighbour_work: the
// sum over cells of the cells their points' links pool, squared (Ready's
// bunny: 1.0e7, 0.13 s; 13,500 polyhedra by vertex: 3e8, 1.1 s).
inline constexpr double max_neighbour_work = 4e9;
Neighbours neighbours(const Mesh& mesh, Kind kind);

// Ready's Laplacian of one chemical, as its formula rule's kernel computes
// it (FormulaOpenCLMeshRD.cpp): -x, then for each of the cell's
// max_neighbors slots in order (the padding too) x[index] * weight added,
// the sum times 4. fused: each `+= x * w` rounded once, as OpenCL C
// contracts it (pocl's clang); else the product and the sum each round.
// The weights are float in both; for double, each is widened first.
std::vector<float> laplacian(const Neighbours& n, const std::vector<float>& x, bool fused);
std::vector<double> laplacian(const Neighbours& n, const std::vector<double>& x, bool fused);

}  // namespace sim::mesh
