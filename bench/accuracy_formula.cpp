// Run time against error for a formula model's integrators (issue 49):
// forward Euler, Heun and RK4 over a range of timesteps, (a) on a model
// with a known answer, a Fourier mode of the heat equation on a torus,
// which decays between the grid's points exactly as exp(lambda t) with
// lambda the stencil's eigenvalue, and (b) on Pearson's Gray-Scott against
// a fine double reference (RK4 at a timestep 64 times smaller than the
// finest measured). Each run is timed alone on one thread (the best of
// three for runs under a second); the cheapest integrator for each error
// is read off the curves.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "accuracy.hpp"
#include "sim/formula/run.hpp"
#include "sim/formula/stability.hpp"
#include "sim/random.hpp"

namespace bench {
namespace {

namespace formula = sim::formula;

const formula::Integrator integrators[] = {formula::Integrator::euler, formula::Integrator::heun,
                                           formula::Integrator::rk4};
const char* const integrator_colours[] = {"#d94801", "#2171b5", "#238b45"};

struct Timed {
    std::vector<sim::Grid<double>> state;
    double seconds;
};

// `rule` run `steps` steps from `start` on one thread: the end and the best time of up to three runs.
Timed timed_run(const formula::Rule& rule, int width, int height, const std::vector<sim::Grid<double>>& start,
                int steps) {
    Timed best{{}, 1e300};
    for (int attempt = 0; attempt < 3; ++attempt) {
        formula::Run run(rule, width, height, start);
        const auto t0 = Clock::now();
        run.step(steps, 1);
        const double seconds = seconds_since(t0);
        if (seconds < best.seconds) {
            best.seconds = seconds;
            best.state.clear();
            for (int c = 0; c < rule.chemicals; ++c) best.state.push_back(run.chemical(c));
        }
        if (best.seconds > 1.0) break;
    }
    return best;
}

double largest_difference(const sim::Grid<double>& a, const sim::Grid<double>& b) {
    double most = 0;
    for (std::size_t i = 0; i < a.size(); ++i) most = std::max(most, std::abs(a.data()[i] - b.data()[i]));
    return most;
}

// The least run time at which a curve's error is at most `error`, along its
// segments on log-log axes; infinity if it never is.
double time_for(const Curve& curve, double error) {
    std::vector<Point> points = curve.points;
    std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.seconds < b.seconds; });
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].error > error) continue;
        if (i == 0) return points[0].seconds;
        const Point& a = points[i - 1];
        const Point& b = points[i];
        const double t = (std::log(error) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
        return std::exp(std::log(a.seconds) + t * (std::log(b.seconds) - std::log(a.seconds)));
    }
    return std::numeric_limits<double>::infinity();
}

// For each error in `targets`, the integrator that reaches it soonest.
nlohmann::json cheapest(const std::vector<Curve>& curves, const std::vector<double>& targets) {
    nlohmann::json out = nlohmann::json::array();
    for (double error : targets) {
        nlohmann::json row = {{"error", error}};
        double best = std::numeric_limits<double>::infinity();
        for (const Curve& c : curves) {
            const double t = time_for(c, error);
            row["seconds"][c.label] = std::isfinite(t) ? nlohmann::json(t) : nlohmann::json(nullptr);
            if (t < best) {
                best = t;
                row["cheapest"] = c.label;
            }
        }
        out.push_back(row);
    }
    return out;
}

}  // namespace

nlohmann::json formula_integrators(Curves& curves) {
    nlohmann::json out;
    // (a) delta_a = D laplacian_a, D = 1, 2-D medium accuracy (Ready's 9
    // points), 128 x 128 torus, the mode cos(2 pi (3 x + 2 y) / 128), to t = 20.
    {
        const int n = 128;
        const double T = 20, kx = 2 * std::numbers::pi * 3 / n, ky = 2 * std::numbers::pi * 2 / n;
        // The 9-point stencil's eigenvalue: (4 (2 cos kx + 2 cos ky) + 4 cos kx cos ky - 20) / 6.
        const double lambda =
            (4 * (2 * std::cos(kx) + 2 * std::cos(ky)) + 4 * std::cos(kx) * std::cos(ky) - 20) / 6;
        sim::Grid<double> start(n, n);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) start(y, x) = std::cos(kx * x + ky * y);
        sim::Grid<double> exact = start;
        for (std::size_t i = 0; i < exact.size(); ++i) exact.data()[i] *= std::exp(lambda * T);
        nlohmann::json rows = nlohmann::json::array();
        std::vector<Curve> made;
        for (int i = 0; i < 3; ++i) {
            Curve curve{formula::integrator_name(integrators[i]), integrator_colours[i], {}};
            for (double timestep : {0.25, 0.125, 0.0625, 0.03125, 0.015625, 0.0078125}) {
                formula::Rule rule;
                rule.chemicals = 1;
                rule.code = "delta_a = laplacian_a;";
                rule.parameters = {{"timestep", timestep}};
                rule.double_precision = true;
                rule.block_x = 1;
                rule.edges = formula::Edges::all(formula::Edge::periodic);
                rule.integrator = integrators[i];
                const int steps = static_cast<int>(std::lround(T / timestep));
                const Timed run = timed_run(rule, n, n, {start}, steps);
                const double error = largest_difference(run.state[0], exact);
                rows.push_back({{"integrator", formula::integrator_name(integrators[i])},
                                {"timestep", timestep},
                                {"steps", steps},
                                {"seconds", run.seconds},
                                {"max_error", error}});
                curve.points.push_back({run.seconds, std::max(error, 1e-17)});
            }
            made.push_back(curve);
        }
        out["heat_mode"] = {{"rows", rows}, {"cheapest", cheapest(made, {1e-3, 1e-6, 1e-9})}};
        curves.integrators_known.insert(curves.integrators_known.end(), made.begin(), made.end());
    }
    // (b) Pearson's Gray-Scott (D_a = 0.2, D_b = 0.1, F = 0.035, K = 0.06),
    // 128 x 128 in double, b raised on a square with noise, to t = 500,
    // against RK4 at a timestep of 1/128.
    {
        const int n = 128;
        const double T = 500;
        formula::Rule rule;
        rule.chemicals = 2;
        rule.code = "delta_a = 0.2 * laplacian_a - a * b * b + 0.035 * (1.0 - a);"
                    "delta_b = 0.1 * laplacian_b + a * b * b - (0.035 + 0.06) * b;";
        rule.double_precision = true;
        rule.block_x = 1;
        rule.edges = formula::Edges::all(formula::Edge::periodic);
        sim::Random rng(49);
        sim::Grid<double> a(n, n, 1.0), b(n, n, 0.0);
        for (int y = n / 2 - 10; y < n / 2 + 10; ++y)
            for (int x = n / 2 - 10; x < n / 2 + 10; ++x) {
                a(y, x) = 0.5 + 0.02 * rng.uniform();
                b(y, x) = 0.25 + 0.02 * rng.uniform();
            }
        const std::vector<sim::Grid<double>> start{a, b};
        auto run_at = [&](formula::Integrator integrator, double timestep) {
            formula::Rule r = rule;
            r.integrator = integrator;
            r.set_parameter("timestep", timestep);
            return timed_run(r, n, n, start, static_cast<int>(std::lround(T / timestep)));
        };
        std::fprintf(stderr, "figgen_accuracy: Gray-Scott's reference, RK4 at 1/128\n");
        const Timed reference = run_at(formula::Integrator::rk4, 1.0 / 128);
        nlohmann::json rows = nlohmann::json::array();
        std::vector<Curve> made;
        for (int i = 0; i < 3; ++i) {
            Curve curve{formula::integrator_name(integrators[i]), integrator_colours[i], {}};
            formula::Rule r = rule;
            r.integrator = integrators[i];
            r.set_parameter("timestep", 1.0);
            const double bound = formula::stability_bound(r, 2, {1.0, 0.0}).timestep;
            for (double timestep : {2.0, 1.0, 0.5, 0.25, 0.125}) {
                // Past the explicit bound (1.875 for Euler and Heun, 2.6 for RK4) a run blows up: said, not drawn.
                if (timestep > bound) {
                    rows.push_back({{"integrator", formula::integrator_name(integrators[i])},
                                    {"timestep", timestep},
                                    {"past_stability_bound", bound}});
                    continue;
                }
                const Timed run = run_at(integrators[i], timestep);
                const double error = std::max(largest_difference(run.state[0], reference.state[0]),
                                              largest_difference(run.state[1], reference.state[1]));
                rows.push_back({{"integrator", formula::integrator_name(integrators[i])},
                                {"timestep", timestep},
                                {"seconds", run.seconds},
                                {"max_error", error}});
                curve.points.push_back({run.seconds, std::max(error, 1e-17)});
            }
            made.push_back(curve);
        }
        out["gray_scott"] = {{"rows", rows},
                             {"reference", {{"integrator", "rk4"}, {"timestep", 1.0 / 128}, {"seconds", reference.seconds}}},
                             {"cheapest", cheapest(made, {1e-2, 1e-4, 1e-6})}};
        curves.integrators_reference.insert(curves.integrators_reference.end(), made.begin(), made.end());
    }
    return out;
}

}  // namespace bench
