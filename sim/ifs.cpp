#include "sim/ifs.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sim/check.hpp"

namespace sim {
namespace {

void require_finite(std::size_t map, const char* coefficient, double value) {
    if (std::isfinite(value)) return;
    throw ParameterError("maps[" + std::to_string(map) + "]." + coefficient, shown(value), "a finite number");
}

// require_integer for counts held in 64 unsigned bits, which a long long may not show.
void require_count(const char* name, std::uint64_t value, std::uint64_t high) {
    if (value <= high) return;
    throw ParameterError(name, std::to_string(value), "an integer from 0 to " + std::to_string(high));
}

}  // namespace

void Ifs::validate() const {
    require_integer("maps", static_cast<long long>(maps.size()), 1, 64);
    double total = 0;
    for (std::size_t m = 0; m < maps.size(); ++m) {
        const AffineMap& map = maps[m];
        require_finite(m, "a", map.a);
        require_finite(m, "b", map.b);
        require_finite(m, "c", map.c);
        require_finite(m, "d", map.d);
        require_finite(m, "e", map.e);
        require_finite(m, "f", map.f);
        const std::string name = "maps[" + std::to_string(m) + "].p";
        require_number(name.c_str(), map.p, 0.0, 1.0);
        total += map.p;
    }
    if (std::abs(total - 1.0) > 1e-9) {
        // Twelve digits: a sum off by 1e-8 must not show as "1".
        std::ostringstream sum;
        sum << std::setprecision(12) << total;
        throw ParameterError("maps", "probabilities summing to " + sum.str(),
                             "probabilities p summing to 1 (within 1e-9)");
    }
}

Ifs barnsley_fern() {
    return Ifs{{
        {0.00, 0.00, 0.00, 0.16, 0.0, 0.00, 0.01},    // stem
        {0.85, 0.04, -0.04, 0.85, 0.0, 1.60, 0.85},   // the fern minus its lowest leaflets, slightly turned
        {0.20, -0.26, 0.23, 0.22, 0.0, 1.60, 0.07},   // lowest left leaflet
        {-0.15, 0.28, 0.26, 0.24, 0.0, 0.44, 0.07},   // lowest right leaflet, mirrored
    }};
}

void ChaosGameParams::validate() const {
    // 1e8 points are 1.6 GB already; more is surely a typo.
    require_count("points", points, 100000000);
    require_count("discard", discard, 100000000);
    require_number("start.x", start.x, -1e300, 1e300);
    require_number("start.y", start.y, -1e300, 1e300);
}

std::size_t pick_map(const Ifs& ifs, double u) {
    double cumulative = 0;
    std::size_t last_positive = 0;
    for (std::size_t m = 0; m < ifs.maps.size(); ++m) {
        if (ifs.maps[m].p <= 0) continue;  // strict "<" below already skips it; this also keeps it out of the fallback
        cumulative += ifs.maps[m].p;
        if (u < cumulative) return m;
        last_positive = m;
    }
    return last_positive;
}

std::vector<glm::dvec2> chaos_game(const Ifs& ifs, const ChaosGameParams& params, Random& rng,
                                   std::vector<std::uint64_t>* map_counts) {
    ifs.validate();
    params.validate();
    if (map_counts) map_counts->assign(ifs.maps.size(), 0);
    std::vector<glm::dvec2> points;
    points.reserve(params.points);
    glm::dvec2 v = params.start;
    const std::uint64_t steps = params.discard + params.points;
    for (std::uint64_t s = 0; s < steps; ++s) {
        const std::size_t m = pick_map(ifs, rng.uniform());
        if (map_counts) ++(*map_counts)[m];
        v = ifs.maps[m].apply(v);
        if (s >= params.discard) points.push_back(v);
        // The health check, every 4096 points and at the end: maps that do
        // not contract send the points to infinity.
        if ((s & 4095) == 4095 || s + 1 == steps)
            if (!(std::abs(v.x) <= 1e100 && std::abs(v.y) <= 1e100))
                throw std::runtime_error("the chaos game went numerically unstable at point " + std::to_string(s + 1) +
                                         " (a coordinate beyond 1e100: the maps do not contract); no image written");
    }
    return points;
}

Density density(const std::vector<glm::dvec2>& points, int width, int height, glm::dvec2 lo, glm::dvec2 hi) {
    require_integer("width", width, 1, 16384);
    require_integer("height", height, 1, 16384);
    require_number("lo.x", lo.x, -1e300, 1e300);
    require_number("lo.y", lo.y, -1e300, 1e300);
    require_number("hi.x", hi.x, lo.x, 1e300);
    require_number("hi.y", hi.y, lo.y, 1e300);
    if (hi.x == lo.x || hi.y == lo.y)
        throw std::invalid_argument("density box is empty: hi must exceed lo on both axes");
    Density out{width, height, lo, hi, std::vector<std::uint32_t>(static_cast<std::size_t>(width) * height, 0)};
    const double sx = width / (hi.x - lo.x), sy = height / (hi.y - lo.y);
    for (const glm::dvec2& v : points) {
        if (!(v.x >= lo.x && v.x <= hi.x && v.y >= lo.y && v.y <= hi.y)) continue;  // also drops NaN
        // x == hi.x would land one past the last column: the closed box puts it in the last.
        const int col = std::min(static_cast<int>((v.x - lo.x) * sx), width - 1);
        const int from_bottom = std::min(static_cast<int>((v.y - lo.y) * sy), height - 1);
        ++out.counts[static_cast<std::size_t>(height - 1 - from_bottom) * width + col];
    }
    return out;
}

}  // namespace sim
