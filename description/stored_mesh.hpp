#pragma once
// The mesh a run starts from when a Ready pattern file is a mesh (.vtu,
// ready/pattern.hpp reads it; or one of figgen's own, figures/meshes/):
// its cells over their points, as VTK holds them, and the chemicals each
// cell holds. A description file cannot name a file to read.

#include <cstdint>
#include <vector>

namespace description {

struct StoredMesh {
    // As sim::mesh::Mesh holds them (sim/mesh/mesh.hpp), checked by the reader.
    std::vector<double> points;            // x, y, z of each point
    bool points_float64 = false;           // the file's points are Float64 (else Float32)
    std::vector<std::int64_t> offsets{0};  // cell c's points: point_ids[offsets[c] .. offsets[c + 1])
    std::vector<std::int64_t> point_ids;
    std::vector<std::uint8_t> types;       // each cell's VTK type
    std::vector<std::int64_t> faces, face_offsets;  // polyhedra's faces, VTK's layout
    int chemical_count = 0;   // how many the file stores
    bool float64 = false;     // Float64 arrays (else Float32)
    std::vector<std::vector<double>> chemicals;  // a value a cell each
    std::size_t cell_count() const { return types.size(); }
};

}  // namespace description
