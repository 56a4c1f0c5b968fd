#pragma once
// A run's state as Ready's pattern files hold it: the rule, its parameters,
// the drawn range and every chemical's cells, on an image or a mesh. A
// scene hands it over; the outputs write it (ready/writers/vti_file.hpp,
// vtu_file.hpp).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/mesh/mesh.hpp"

namespace ready {

// What a VTI file of an image's run, or a VTU file of a mesh's, holds.
struct ReadyState {
    std::string rule_name;    // <rule name=...>
    std::string description;  // <description>
    std::string formula;
    std::string kernel;  // a kernel rule's whole kernel, in place of the formula
    std::string accuracy = "medium";
    bool wrap = true;
    int block_x = 4;
    std::vector<std::pair<std::string, double>> parameters;
    std::string active_chemical = "a";
    std::optional<double> low, high;  // the drawn range of the active chemical
    int width = 0, height = 0, depth = 1;
    bool float64 = false;
    std::vector<std::vector<double>> chemicals;  // as StoredStart: x fastest, then y, then z; or by cell
    // A mesh run's: the cells (the scene's own, alive while the outputs are
    // written; null for an image) and whose neighbours a cell's are.
    const sim::mesh::Mesh* mesh = nullptr;
    bool points_float64 = false;  // its points as Float64 (else Float32, as Ready's own)
    std::string neighborhood = "vertex";  // vertex, edge or face
};

}  // namespace ready
