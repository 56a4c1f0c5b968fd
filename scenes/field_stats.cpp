#include "scenes/field_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "render/digest.hpp"

namespace scenes {

nlohmann::json field_statistics(const sim::Grid<double>& field) {
    const auto& cells = field.cells();
    const auto [lo, hi] = std::minmax_element(cells.begin(), cells.end());
    double sum = 0.0;
    for (double v : cells) sum += v;
    return {{"min", *lo}, {"max", *hi}, {"mean", sum / double(cells.size())}, {"sum", sum}};
}

std::string state_hash(const sim::Grid<double>& field) {
    return render::sha256_hex(field.data(), field.size() * sizeof(double));
}

std::string state_hash(const std::vector<double>& values) {
    return render::sha256_hex(values.data(), values.size() * sizeof(double));
}

void require_finite(const sim::Grid<double>& field, const std::string& model, int step, double bound) {
    for (double v : field.cells()) {
        if (!std::isfinite(v))
            throw std::runtime_error(model + " went numerically unstable at step " + std::to_string(step) +
                                     " (non-finite values); no image written");
        if (std::abs(v) > bound) {
            char detail[96];
            std::snprintf(detail, sizeof detail, " (a value of %g, beyond %g)", v, bound);
            throw std::runtime_error(model + " went numerically unstable at step " + std::to_string(step) + detail +
                                     "; no image written");
        }
    }
}

}  // namespace scenes
