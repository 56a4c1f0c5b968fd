#include "sim/phyllotaxis.hpp"

#include <cmath>
#include <stdexcept>

#include "sim/check.hpp"

namespace sim {

void PhyllotaxisParams::validate() const {
    require_integer("seeds", seeds, 1, 100000);
    require_number("divergence", divergence, 1e-9, 360 - 1e-9);
    require_number("spacing", spacing, 1e-9, 1e9);
}

std::vector<Seed> vogel_spiral(const PhyllotaxisParams& params) {
    params.validate();
    std::vector<Seed> seeds;
    seeds.reserve(static_cast<std::size_t>(params.seeds));
    const double phi = params.divergence * (M_PI / 180.0);
    for (int n = 0; n < params.seeds; ++n) {
        const double r = params.spacing * std::sqrt(double(n));
        const double theta = n * phi;
        seeds.push_back({n, {r * std::cos(theta), r * std::sin(theta)}, theta});
    }
    return seeds;
}

}  // namespace sim
