#pragma once
// A formula run's state as Ready's pattern files hold it: the rule, its
// parameters, the drawn range and every chemical's cells. A scene hands it
// over; the outputs write it (ready/writers/vti_file.hpp).

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ready {

// What a VTI file of a formula run holds.
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
    std::vector<std::vector<double>> chemicals;  // as StoredStart: x fastest, then y, then z
};

}  // namespace ready
