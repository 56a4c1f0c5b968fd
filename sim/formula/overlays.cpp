#include "sim/formula/overlays.hpp"

#include "sim/formula/rule.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
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

namespace {

// What every sample of a pattern shares: each overlay's noise generator and
// parameter value, made once.
struct Prepared {
    std::vector<std::unique_ptr<Perlin>> perlin;
    std::vector<double> parameter_values;
};

Prepared prepare(const Pattern& pattern, int chemicals, const std::vector<std::pair<std::string, double>>& parameters,
                 Random& rng) {
    Prepared p;
    for (const Overlay& o : pattern.overlays)
        p.perlin.push_back(o.fill.kind == Fill::Kind::perlin_noise ? std::make_unique<Perlin>(rng) : nullptr);
    for (const Overlay& o : pattern.overlays) {
        double value = 0;
        if (o.fill.kind == Fill::Kind::parameter) {
            bool found = false;
            for (const auto& [name, v] : parameters)
                if (name == o.fill.parameter) value = v, found = true;
            if (!found) throw std::invalid_argument("a parameter fill names \"" + o.fill.parameter + "\", which the rule does not have");
        }
        if (o.fill.kind == Fill::Kind::other_chemical && (o.fill.chemical < 0 || o.fill.chemical >= chemicals))
            throw std::invalid_argument("an other_chemical fill names a chemical the rule does not have");
        p.parameter_values.push_back(value);
    }
    return p;
}

// Overlay k's value at a sample (fx, fy, fz) of an arena X x Y x Z whose
// axes `checked` count, over `target`; nullopt where its shapes leave the sample out.
// `pixel` is the sample's cell on a grid (none on a mesh: no pixel holds it).
std::optional<double> overlay_at(const Overlay& o, std::size_t k, const Prepared& p, const std::vector<double>& values,
                                 double target, double fx, double fy, double fz, double X, double Y, double Z,
                                 const bool checked[3], const int* pixel, Random& rng) {
    const double largest = std::max({X, Y, Z});
    std::optional<double> out;
    for (const Shape& s : o.shapes) {
        bool inside = false;
        switch (s.kind) {
        case Shape::Kind::everywhere: inside = true; break;
        case Shape::Kind::rectangle:
            inside = true;
            if (checked[0]) inside = inside && fx / X >= s.a[0] && fx / X <= s.b[0];
            if (checked[1]) inside = inside && fy / Y >= s.a[1] && fy / Y <= s.b[1];
            if (checked[2]) inside = inside && fz / Z >= s.a[2] && fz / Z <= s.b[2];
            break;
        case Shape::Kind::circle: {
            const double ex = checked[0] ? fx - s.a[0] * X : 0.0, ey = checked[1] ? fy - s.a[1] * Y : 0.0,
                         ez = checked[2] ? fz - s.a[2] * Z : 0.0;
            inside = hypot3(ex, ey, ez) < s.radius * largest;
            break;
        }
        case Shape::Kind::pixel:
            inside = pixel && pixel[0] == s.pixel[0] && (!checked[1] || pixel[1] == s.pixel[1]) &&
                     (!checked[2] || pixel[2] == s.pixel[2]);
            break;
        }
        if (!inside) continue;
        const Fill& f = o.fill;
        double v = 0;
        switch (f.kind) {
        case Fill::Kind::constant: v = f.value; break;
        case Fill::Kind::white_noise: v = f.low + (f.high - f.low) * rng.uniform(); break;
        case Fill::Kind::perlin_noise: v = p.perlin[k]->octaves01(fx / f.scale, fy / f.scale, fz / f.scale, f.octaves); break;
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
        case Fill::Kind::other_chemical: v = values[static_cast<std::size_t>(f.chemical)]; break;
        case Fill::Kind::parameter: v = p.parameter_values[k]; break;
        }
        switch (o.operation) {
        case Overlay::Operation::overwrite: target = v; break;
        case Overlay::Operation::add: target += v; break;
        case Overlay::Operation::subtract: target -= v; break;
        case Overlay::Operation::multiply: target *= v; break;
        case Overlay::Operation::divide: target /= v; break;
        }
        out = target;
    }
    return out;
}

}  // namespace

void apply_pattern(const Pattern& pattern, std::vector<Grid<double>>& chemicals, int depth,
                   const std::vector<std::pair<std::string, double>>& parameters, bool double_precision, Random& rng,
                   std::array<double, 3> offset) {
    if (chemicals.empty()) return;
    if (depth < 1 || chemicals.front().rows() % depth != 0)
        throw std::invalid_argument("a grid of " + std::to_string(chemicals.front().rows()) + " rows is not " +
                                    std::to_string(depth) + " planes");
    const int width = chemicals.front().cols(), height = chemicals.front().rows() / depth;
    const double X = width, Y = height, Z = depth;
    const int dimensions = dimensionality(width, height, depth);
    const bool checked[3] = {true, dimensions >= 2, dimensions >= 3};
    const auto stored = [&](double v) { return double_precision ? v : static_cast<double>(static_cast<float>(v)); };
    if (pattern.zero_first)
        for (Grid<double>& g : chemicals) g.fill(0.0);
    const int n = static_cast<int>(chemicals.size());
    const Prepared prepared = prepare(pattern, n, parameters, rng);
    std::vector<double> values(static_cast<std::size_t>(n));
    for (int z = 0; z < depth; ++z)
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (std::size_t k = 0; k < pattern.overlays.size(); ++k) {
                const Overlay& o = pattern.overlays[k];
                if (o.chemical < 0 || o.chemical >= n) continue;  // as Ready: an overlay of a chemical not there is skipped
                const int row = z * height + y;
                for (int c = 0; c < n; ++c) values[static_cast<std::size_t>(c)] = chemicals[static_cast<std::size_t>(c)](row, x);
                const int pixel[3] = {x, y, z};
                const auto v = overlay_at(o, k, prepared, values, values[static_cast<std::size_t>(o.chemical)],
                                          x + offset[0], y + offset[1], z + offset[2], X, Y, Z, checked, pixel, rng);
                if (v) chemicals[static_cast<std::size_t>(o.chemical)](row, x) = stored(*v);
            }
}

void apply_pattern_to_cells(const Pattern& pattern, std::vector<std::vector<double>>& chemicals,
                            const std::vector<std::array<double, 3>>& centres, std::array<double, 3> extent,
                            const std::vector<std::pair<std::string, double>>& parameters, bool double_precision,
                            Random& rng) {
    if (chemicals.empty()) return;
    const auto stored = [&](double v) { return double_precision ? v : static_cast<double>(static_cast<float>(v)); };
    if (pattern.zero_first)
        for (auto& c : chemicals) std::fill(c.begin(), c.end(), 0.0);
    const int n = static_cast<int>(chemicals.size());
    const Prepared prepared = prepare(pattern, n, parameters, rng);
    const bool checked[3] = {extent[0] > 0, extent[1] > 0, extent[2] > 0};
    std::vector<double> values(static_cast<std::size_t>(n));
    for (std::size_t cell = 0; cell < centres.size(); ++cell)
        for (std::size_t k = 0; k < pattern.overlays.size(); ++k) {
            const Overlay& o = pattern.overlays[k];
            if (o.chemical < 0 || o.chemical >= n) continue;
            for (int c = 0; c < n; ++c) values[static_cast<std::size_t>(c)] = chemicals[static_cast<std::size_t>(c)][cell];
            const std::array<double, 3>& p = centres[cell];
            const auto v = overlay_at(o, k, prepared, values, values[static_cast<std::size_t>(o.chemical)], p[0], p[1], p[2],
                                      extent[0], extent[1], extent[2], checked, nullptr, rng);
            if (v) chemicals[static_cast<std::size_t>(o.chemical)][cell] = stored(*v);
        }
}

}  // namespace sim::formula
