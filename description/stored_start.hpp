#pragma once
// The arrays a run starts from when a Ready pattern file stores them
// (ready/pattern.hpp reads them): a description file cannot name one.

#include <vector>

namespace description {

// The chemicals a file stores, a, b, c, ... in order. Known by their
// shape first (the figure is checked, its memory estimated), decoded only
// once that passed (app/render/targets.hpp).
struct StoredStart {
    int width = 0, height = 0, depth = 1;
    int chemical_count = 0;  // how many the file stores
    bool float64 = false;    // Float64 arrays (else Float32)
    std::vector<std::vector<double>> chemicals;  // width * height * depth values each, x fastest, then y, then z; empty until decoded
    bool decoded() const { return !chemicals.empty(); }
};

}  // namespace description
