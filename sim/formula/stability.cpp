#include "sim/formula/stability.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "sim/formula/run.hpp"

namespace sim::formula {

namespace {

// The integrator's amplification of a mode whose rate times the timestep is z.
std::complex<double> amplification(Integrator integrator, std::complex<double> z) {
    switch (integrator) {
    case Integrator::euler: return 1.0 + z;
    case Integrator::heun: return 1.0 + z + z * z / 2.0;
    case Integrator::rk4: return 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
    }
    return 1.0 + z;
}

// The largest t with |R(s rate)| <= 1 for every s in (0, t]: stepped out
// to past the real axis' widest reach (RK4's 2.79) and refined by bisection.
double stable_until(Integrator integrator, std::complex<double> rate) {
    const double size = std::abs(rate);
    if (size < 1e-300) return std::numeric_limits<double>::infinity();
    // A real rate: the region's reach along the real axis (none on the positive side).
    if (std::abs(rate.imag()) <= 1e-12 * size) {
        if (rate.real() > 0) return 0;
        const double reach = integrator == Integrator::rk4 ? 2.785293563405282 : 2.0;
        return reach / size;
    }
    auto stable = [&](double t) { return std::abs(amplification(integrator, t * rate)) <= 1 + 1e-12; };
    const int steps = 512;
    const double reach = 4.0 / size;
    double lo = 0;
    for (int i = 1; i <= steps; ++i) {
        const double t = reach * i / steps;
        if (!stable(t)) {
            double hi = t;
            for (int k = 0; k < 60; ++k) {
                const double mid = 0.5 * (lo + hi);
                (stable(mid) ? lo : hi) = mid;
            }
            // A region that only touches the origin (forward Euler on an
            // imaginary rate): |R| grows from the first step, however small.
            return lo * size < 1e-4 ? 0.0 : lo;
        }
        lo = t;
    }
    return std::numeric_limits<double>::infinity();  // stable as far as any integrator's region reaches
}

}  // namespace

StabilityBound stability_bound(const Rule& rule, int dimensions, const std::vector<double>& base) {
    if (static_cast<int>(base.size()) != rule.chemicals)
        throw std::invalid_argument("stability_bound: one base value a chemical");
    StabilityBound bound;
    const double given = rule.parameter("timestep");
    if (!(given > 0) || !std::isfinite(given)) return bound;
    // The timestep the probe's step takes, as its formula reads it (0.3 is 0.30000001).
    const double timestep = formula_value(given);
    // The probe: the rule in double on a periodic grid of 8 a side, stepped once by Euler.
    Rule probe = rule;
    probe.double_precision = true;
    probe.ready_edges = false;
    probe.wrap = true;
    probe.edges.reset();  // a torus: the bound is the stencils' own
    probe.integrator = Integrator::euler;
    const int n = 8, width = n, height = dimensions >= 2 ? n : 1, depth = dimensions == 3 ? n : 1;
    const int rows = height * depth;
    auto deltas = [&](int raised, double by) {
        std::vector<Grid<double>> start;
        for (int c = 0; c < rule.chemicals; ++c) start.emplace_back(rows, width, base[static_cast<std::size_t>(c)]);
        if (raised >= 0) start[static_cast<std::size_t>(raised)](0, 0) += by;
        Run run(probe, width, height, depth, start);
        run.step(1, 1);
        std::vector<Grid<double>> d;
        for (int c = 0; c < rule.chemicals; ++c) {
            Grid<double> g = run.chemical(c);
            for (int y = 0; y < rows; ++y)
                for (int x = 0; x < width; ++x) g(y, x) = (g(y, x) - start[static_cast<std::size_t>(c)](y, x)) / timestep;
            d.push_back(std::move(g));
        }
        return d;
    };
    const std::vector<Grid<double>> uniform = deltas(-1, 0);
    // The taps of delta_c's response to a raise of chemical e, at signed offsets.
    struct Tap {
        int dx, dy, dz;
        double weight;
    };
    const int chemicals = rule.chemicals;
    std::vector<std::vector<Tap>> taps(static_cast<std::size_t>(chemicals * chemicals));  // [c * chemicals + e]
    for (int e = 0; e < chemicals; ++e) {
        const double by = 1e-4 * std::max(1.0, std::abs(base[static_cast<std::size_t>(e)]));
        const std::vector<Grid<double>> raised = deltas(e, by);
        for (int c = 0; c < chemicals; ++c)
            for (int z = 0; z < depth; ++z)
                for (int y = 0; y < height; ++y)
                    for (int x = 0; x < width; ++x) {
                        const int row = z * height + y;
                        const double w = (raised[static_cast<std::size_t>(c)](row, x) -
                                          uniform[static_cast<std::size_t>(c)](row, x)) / by;
                        if (std::abs(w) < 1e-7) continue;
                        auto signed_offset = [&](int i) { return i > n / 2 ? i - n : i; };
                        taps[static_cast<std::size_t>(c * chemicals + e)].push_back(
                            {signed_offset(x), signed_offset(y), signed_offset(z), w});
                    }
    }
    auto symbol = [&](int c, int e, double tx, double ty, double tz) {
        std::complex<double> s = 0;
        for (const Tap& t : taps[static_cast<std::size_t>(c * chemicals + e)])
            s += t.weight * std::polar(1.0, -(tx * t.dx + ty * t.dy + tz * t.dz));
        return s;
    };
    // The rates of mode theta: the eigenvalues of the chemicals' symbols
    // less their values at theta = 0. One chemical's own, or two coupled
    // (Schroedinger's a and b) exactly; with more, each chemical's own
    // (bound.coupled says when that leaves terms out).
    std::vector<std::complex<double>> at_zero(static_cast<std::size_t>(chemicals * chemicals));
    for (int c = 0; c < chemicals; ++c)
        for (int e = 0; e < chemicals; ++e) at_zero[static_cast<std::size_t>(c * chemicals + e)] = symbol(c, e, 0, 0, 0);
    const int samples = dimensions == 3 ? 24 : 64;
    const int sy = dimensions >= 2 ? samples : 1, sz = dimensions == 3 ? samples : 1;
    auto angle = [](int m, int count) { return count == 1 ? 0.0 : -std::numbers::pi + 2 * std::numbers::pi * m / count; };
    auto consider = [&](std::complex<double> rate, int chemical, double tx, double ty, double tz) {
        if (std::abs(rate) < 1e-9) return;
        const double t = stable_until(rule.integrator, rate);
        if (t >= bound.timestep) return;
        bound.timestep = t;
        bound.chemical = chemical_name(chemical);
        bound.theta = {tx};
        if (dimensions >= 2) bound.theta.push_back(ty);
        if (dimensions == 3) bound.theta.push_back(tz);
        bound.rate_real = rate.real();
        bound.rate_imaginary = rate.imag();
    };
    // The chemicals whose change reads a neighbour, or whose neighbours
    // another's change reads: only they have rates (a tap at the cell
    // itself is the same at every theta).
    std::vector<int> active;
    for (int k = 0; k < chemicals; ++k) {
        bool spatial = false;
        for (int e = 0; e < chemicals; ++e)
            for (const auto* list : {&taps[static_cast<std::size_t>(k * chemicals + e)], &taps[static_cast<std::size_t>(e * chemicals + k)]})
                for (const Tap& t : *list) spatial = spatial || t.dx != 0 || t.dy != 0 || t.dz != 0;
        if (spatial) active.push_back(k);
    }
    for (int k = 0; k < sz; ++k)
        for (int j = 0; j < sy; ++j)
            for (int i = 0; i < samples; ++i) {
                const double tx = angle(i, samples), ty = angle(j, sy), tz = angle(k, sz);
                auto m = [&](int c, int e) { return symbol(c, e, tx, ty, tz) - at_zero[static_cast<std::size_t>(c * chemicals + e)]; };
                if (active.size() == 2) {
                    const int p = active[0], q = active[1];
                    const std::complex<double> a = m(p, p), b = m(p, q), c = m(q, p), d = m(q, q);
                    const std::complex<double> half = 0.5 * (a + d), root = std::sqrt(0.25 * (a - d) * (a - d) + b * c);
                    const bool coupled = std::abs(b) > 1e-9 || std::abs(c) > 1e-9;
                    consider(half + root, coupled || std::abs(half + root - a) < 1e-9 ? p : q, tx, ty, tz);
                    consider(half - root, coupled || std::abs(half - root - a) < 1e-9 ? p : q, tx, ty, tz);
                    continue;
                }
                for (int c : active) {
                    for (int e : active)
                        if (e != c && std::abs(m(c, e)) > 1e-9) bound.coupled = true;
                    consider(m(c, c), c, tx, ty, tz);
                }
            }
    return bound;
}

}  // namespace sim::formula
