#pragma once
// Per-panel numbers for a real-valued field: what the metadata records.

#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <vector>

#include "sim/check.hpp"
#include "sim/grid.hpp"

namespace scenes {

// min, max, mean and sum of the field.
nlohmann::json field_statistics(const sim::Grid<double>& field);

// SHA-256 of the field's cells as stored (row-major IEEE doubles).
std::string state_hash(const sim::Grid<double>& field);

// SHA-256 of numbers as stored (IEEE doubles, in order): the state of what a
// plot, a point set or a turtle drawing is made from. Integers the picture
// uses (counts, levels) go in as doubles, exactly.
std::string state_hash(const std::vector<double>& values);

// The health check every stepping scene makes (sim/check.hpp).
using sim::require_finite;

}  // namespace scenes
