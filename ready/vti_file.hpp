#pragma once
// A formula run's last step as Ready writes its own pattern files (--format
// vti): VTK XML ImageData with the <RD> element that holds the rule and its
// parameters, apply_when_loading="false", so Ready, ParaView and figgen
// continue from it.

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
    std::string accuracy = "medium";
    bool wrap = true;
    int block_x = 4;
    std::vector<std::pair<std::string, double>> parameters;
    std::string active_chemical = "a";
    std::optional<double> low, high;  // the drawn range of the active chemical
    int width = 0, height = 0;
    bool float64 = false;
    std::vector<std::vector<double>> chemicals;  // as StoredStart
};

// The file's text: VTK XML ImageData, version 1.0, UInt64 headers, binary
// zlib-compressed blocks of 32 KiB, as VTK 9's writer makes Ready's files.
std::string ready_vti(const ReadyState& state);

}  // namespace ready
