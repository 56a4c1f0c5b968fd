#pragma once
// Per-panel numbers for a real-valued field: what the metadata records and
// what guards against writing an image of a model that blew up.

#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <vector>

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

// Throws std::runtime_error naming the model and step if any cell is NaN or
// infinite, or farther than `bound` from 0: a model that went unstable never
// reaches an image.
void require_finite(const sim::Grid<double>& field, const std::string& model, int step,
                    double bound = std::numeric_limits<double>::infinity());

}  // namespace scenes
