#include "scenes/helpers/field_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "base/digest.hpp"

namespace scenes {

nlohmann::json field_statistics(const sim::Grid<double>& field) {
    const auto& cells = field.cells();
    const auto [lo, hi] = std::minmax_element(cells.begin(), cells.end());
    double sum = 0.0;
    for (double v : cells) sum += v;
    return {{"min", *lo}, {"max", *hi}, {"mean", sum / double(cells.size())}, {"sum", sum}};
}

std::string state_hash(const sim::Grid<double>& field) {
    return base::sha256_hex(field.data(), field.size() * sizeof(double));
}

std::string state_hash(const std::vector<double>& values) {
    return base::sha256_hex(values.data(), values.size() * sizeof(double));
}


}  // namespace scenes
