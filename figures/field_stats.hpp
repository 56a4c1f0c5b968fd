#pragma once
// Per-panel numbers for a real-valued field: what the metadata records and
// what guards against writing an image of a model that blew up.

#include <nlohmann/json.hpp>
#include <limits>
#include <string>

#include "sim/grid.hpp"

namespace figures {

// min, max, mean and sum of the field.
nlohmann::json field_statistics(const sim::Grid<double>& field);

// SHA-256 of the field's cells as stored (row-major IEEE doubles).
std::string state_hash(const sim::Grid<double>& field);

// Throws std::runtime_error naming the model and step if any cell is NaN or
// infinite, or farther than `bound` from 0: a model that went unstable never
// reaches an image.
void require_finite(const sim::Grid<double>& field, const std::string& model, int step,
                    double bound = std::numeric_limits<double>::infinity());

}  // namespace figures
