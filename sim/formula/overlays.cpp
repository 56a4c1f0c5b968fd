#include "sim/formula/overlays.hpp"

#include "sim/formula/rule.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace sim::formula {

namespace {

double hypot3(double x, double y, double z) {
    return std::sqrt(x * x + y * y + z * z);
}

// Ken Perlin's improved noise (2002) over a permutation drawn from the
// run's generator, in octaves of doubling frequency and halving amplitude,
// mapped to [0, 1] as Ready's generator maps it.
class Perlin {
public:
    explicit Perlin(Random& rng) {
        std::iota(p_, p_ + 256, 0);
        for (int i = 255; i > 0; --i) std::swap(p_[i], p_[rng.below(static_cast<std::uint64_t>(i) + 1)]);
        for (int i = 0; i < 256; ++i) p_[256 + i] = p_[i];
    }

    double octaves01(double x, double y, double z, int octaves) const {
        double sum = 0, amplitude = 1;
        for (int i = 0; i < octaves; ++i) {
            sum += noise(x, y, z) * amplitude;
            x *= 2, y *= 2, z *= 2;
            amplitude *= 0.5;
        }
        return std::clamp(sum * 0.5 + 0.5, 0.0, 1.0);
    }

private:
    static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
    static double lerp(double t, double a, double b) { return a + t * (b - a); }
    static double grad(int hash, double x, double y, double z) {
        const int h = hash & 15;
        const double u = h < 8 ? x : y, v = h < 4 ? y : h == 12 || h == 14 ? x : z;
        return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
    }
    double noise(double x, double y, double z) const {
        const int X = static_cast<int>(std::floor(x)) & 255, Y = static_cast<int>(std::floor(y)) & 255,
                  Z = static_cast<int>(std::floor(z)) & 255;
        x -= std::floor(x), y -= std::floor(y), z -= std::floor(z);
        const double u = fade(x), v = fade(y), w = fade(z);
        const int A = p_[X] + Y, AA = p_[A] + Z, AB = p_[A + 1] + Z, B = p_[X + 1] + Y, BA = p_[B] + Z,
                  BB = p_[B + 1] + Z;
        return lerp(w,
                    lerp(v, lerp(u, grad(p_[AA], x, y, z), grad(p_[BA], x - 1, y, z)),
                         lerp(u, grad(p_[AB], x, y - 1, z), grad(p_[BB], x - 1, y - 1, z))),
                    lerp(v, lerp(u, grad(p_[AA + 1], x, y, z - 1), grad(p_[BA + 1], x - 1, y, z - 1)),
                         lerp(u, grad(p_[AB + 1], x, y - 1, z - 1), grad(p_[BB + 1], x - 1, y - 1, z - 1))));
    }
    int p_[512];
};

}  // namespace

std::vector<std::pair<std::string, Overlay::Operation>> operation_names() {
    using O = Overlay::Operation;
    return {{"overwrite", O::overwrite},
            {"add", O::add},
            {"subtract", O::subtract},
            {"multiply", O::multiply},
            {"divide", O::divide}};
}

std::vector<std::pair<std::string, Fill::Kind>> fill_names() {
    using K = Fill::Kind;
    return {{"constant", K::constant},
            {"white_noise", K::white_noise},
            {"perlin_noise", K::perlin_noise},
            {"linear_gradient", K::linear_gradient},
            {"radial_gradient", K::radial_gradient},
            {"gaussian", K::gaussian},
            {"sine", K::sine},
            {"other_chemical", K::other_chemical},
            {"parameter", K::parameter}};
}

std::vector<std::pair<std::string, Shape::Kind>> shape_names() {
    using K = Shape::Kind;
    return {{"everywhere", K::everywhere}, {"rectangle", K::rectangle}, {"circle", K::circle}, {"pixel", K::pixel}};
}

void apply_pattern(const Pattern& pattern, std::vector<Grid<double>>& chemicals, int depth,
                   const std::vector<std::pair<std::string, double>>& parameters, bool double_precision, Random& rng,
                   std::array<double, 3> offset) {
    if (chemicals.empty()) return;
    if (depth < 1 || chemicals.front().rows() % depth != 0)
        throw std::invalid_argument("a grid of " + std::to_string(chemicals.front().rows()) + " rows is not " +
                                    std::to_string(depth) + " planes");
    const int width = chemicals.front().cols(), height = chemicals.front().rows() / depth;
    const double X = width, Y = height, Z = depth, largest = std::max({X, Y, Z});
    const int dimensions = dimensionality(width, height, depth);
    const auto stored = [&](double v) { return double_precision ? v : static_cast<double>(static_cast<float>(v)); };
    if (pattern.zero_first)
        for (Grid<double>& g : chemicals) g.fill(0.0);
    // Each overlay's noise generator, made once.
    std::vector<std::unique_ptr<Perlin>> perlin;
    for (const Overlay& o : pattern.overlays)
        perlin.push_back(o.fill.kind == Fill::Kind::perlin_noise ? std::make_unique<Perlin>(rng) : nullptr);
    std::vector<double> parameter_values;
    for (const Overlay& o : pattern.overlays) {
        double value = 0;
        if (o.fill.kind == Fill::Kind::parameter) {
            bool found = false;
            for (const auto& [name, v] : parameters)
                if (name == o.fill.parameter) value = v, found = true;
            if (!found) throw std::invalid_argument("a parameter fill names \"" + o.fill.parameter + "\", which the rule does not have");
        }
        if (o.fill.kind == Fill::Kind::other_chemical && (o.fill.chemical < 0 || o.fill.chemical >= static_cast<int>(chemicals.size())))
            throw std::invalid_argument("an other_chemical fill names a chemical the rule does not have");
        parameter_values.push_back(value);
    }
    const int n = static_cast<int>(chemicals.size());
    std::vector<double> values(static_cast<std::size_t>(n));
    for (int z = 0; z < depth; ++z)
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (std::size_t k = 0; k < pattern.overlays.size(); ++k) {
                const Overlay& o = pattern.overlays[k];
                if (o.chemical < 0 || o.chemical >= n) continue;  // as Ready: an overlay of a chemical not there is skipped
                const int row = z * height + y;
                for (int c = 0; c < n; ++c) values[c] = chemicals[c](row, x);
                double& target = values[o.chemical];
                const double fx = x + offset[0], fy = y + offset[1], fz = z + offset[2];
                for (const Shape& s : o.shapes) {
                    bool inside = false;
                    switch (s.kind) {
                    case Shape::Kind::everywhere: inside = true; break;
                    case Shape::Kind::rectangle:
                        inside = fx / X >= s.a[0] && fx / X <= s.b[0];
                        if (dimensions >= 2) inside = inside && fy / Y >= s.a[1] && fy / Y <= s.b[1];
                        if (dimensions >= 3) inside = inside && fz / Z >= s.a[2] && fz / Z <= s.b[2];
                        break;
                    case Shape::Kind::circle: {
                        const double ex = fx - s.a[0] * X, ey = dimensions >= 2 ? fy - s.a[1] * Y : 0.0,
                                     ez = dimensions >= 3 ? fz - s.a[2] * Z : 0.0;
                        inside = hypot3(ex, ey, ez) < s.radius * largest;
                        break;
                    }
                    case Shape::Kind::pixel:
                        inside = x == s.pixel[0] && (dimensions < 2 || y == s.pixel[1]) &&
                                 (dimensions < 3 || z == s.pixel[2]);
                        break;
                    }
                    if (!inside) continue;
                    const Fill& f = o.fill;
                    double v = 0;
                    switch (f.kind) {
                    case Fill::Kind::constant: v = f.value; break;
                    case Fill::Kind::white_noise: v = f.low + (f.high - f.low) * rng.uniform(); break;
                    case Fill::Kind::perlin_noise: v = perlin[k]->octaves01(fx / f.scale, fy / f.scale, fz / f.scale, f.octaves); break;
                    case Fill::Kind::linear_gradient:
                    case Fill::Kind::sine: {
                        const double bx = f.p2[0] - f.p1[0], by = f.p2[1] - f.p1[1], bz = f.p2[2] - f.p1[2];
                        const double length = hypot3(bx, by, bz);
                        const double along = length > 0 ? ((fx / X - f.p1[0]) * bx / length + (fy / Y - f.p1[1]) * by / length +
                                                           (fz / Z - f.p1[2]) * bz / length) / length
                                                        : 0.0;
                        v = f.kind == Fill::Kind::sine ? f.amplitude * std::sin(along * 2.0 * std::numbers::pi - f.phase)
                                                       : f.val1 + (f.val2 - f.val1) * along;
                        break;
                    }
                    case Fill::Kind::radial_gradient: {
                        const double d = hypot3(fx - f.p1[0] * X, fy - f.p1[1] * Y, fz - f.p1[2] * Z);
                        const double r = hypot3((f.p2[0] - f.p1[0]) * X, (f.p2[1] - f.p1[1]) * Y, (f.p2[2] - f.p1[2]) * Z);
                        v = f.val1 + (f.val2 - f.val1) * (r > 0 ? d / r : 0.0);
                        break;
                    }
                    case Fill::Kind::gaussian: {
                        const double sigma = f.sigma * largest;
                        const double d = hypot3(f.p1[0] * X - fx, f.p1[1] * Y - fy, f.p1[2] * Z - fz);
                        v = f.height * std::exp(-d * d / (2.0 * sigma * sigma));
                        break;
                    }
                    case Fill::Kind::other_chemical: v = values[f.chemical]; break;
                    case Fill::Kind::parameter: v = parameter_values[k]; break;
                    }
                    switch (o.operation) {
                    case Overlay::Operation::overwrite: target = v; break;
                    case Overlay::Operation::add: target += v; break;
                    case Overlay::Operation::subtract: target -= v; break;
                    case Overlay::Operation::multiply: target *= v; break;
                    case Overlay::Operation::divide: target /= v; break;
                    }
                }
                chemicals[o.chemical](row, x) = stored(target);
            }
}

}  // namespace sim::formula
