// Run time against error for the models and estimators: each method runs at
// growing cost and its error is measured against an independently known
// value (an exact solution, a double-precision run, a published constant).
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>

#include "accuracy.hpp"
#include "sim/cell1d.hpp"
#include "sim/diffusion.hpp"
#include "sim/diffusion_kernel.hpp"
#include "sim/fractal.hpp"
#include "sim/gray_scott.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/percolation.hpp"
#include "sim/percolation_threshold.hpp"
#include "sim/random.hpp"

namespace bench {
namespace {

constexpr double exact_p_c = 0.59274621;             // Newman & Ziff 2000
constexpr double cluster_dimension = 91.0 / 48.0;  // the incipient infinite cluster, d = 2

struct Difference {
    double max, rms;
};

Difference difference(const sim::Grid<double>& x, const sim::Grid<double>& y) {
    double worst = 0, squares = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double d = std::abs(x.data()[i] - y.data()[i]);
        worst = std::max(worst, d);
        squares += d * d;
    }
    return {worst, std::sqrt(squares / double(x.size()))};
}

// Diffusion's exact solution on the n x n torus, in long double (64-bit
// mantissa, so its own rounding sits far below a double run's): the 5-point
// update multiplies Fourier mode (u, v) by g = 1 + r (2 cos 2pi u/n + 2 cos
// 2pi v/n - 4) each step.
class ExactDiffusion {
public:
    ExactDiffusion(const sim::Grid<double>& start, double r) : n_(start.rows()), r_(r), modes_(n_ * n_) {
        // The 2-D DFT, separably: rows, then columns.
        std::vector<std::complex<long double>> rows(n_ * n_);
        for (int i = 0; i < n_; ++i)
            for (int v = 0; v < n_; ++v)
                for (int j = 0; j < n_; ++j) rows[i * n_ + v] += (long double)start(i, j) * twiddle(-v * j);
        for (int u = 0; u < n_; ++u)
            for (int v = 0; v < n_; ++v)
                for (int i = 0; i < n_; ++i) modes_[u * n_ + v] += rows[i * n_ + v] * twiddle(-u * i);
    }

    // The state at (i, j) after `steps` steps.
    double at(int i, int j, int steps) const {
        std::complex<long double> sum = 0;
        for (int u = 0; u < n_; ++u)
            for (int v = 0; v < n_; ++v) {
                const long double g = 1 + r_ * (2 * cosl(angle(u)) + 2 * cosl(angle(v)) - 4);
                sum += modes_[u * n_ + v] * powl(g, steps) * twiddle(u * i + v * j);
            }
        return double(sum.real() / ((long double)n_ * n_));
    }

private:
    long double angle(long k) const { return 2 * std::numbers::pi_v<long double> * (k % n_) / n_; }
    std::complex<long double> twiddle(long k) const { return std::polar(1.0L, angle(k)); }

    int n_;
    long double r_;
    std::vector<std::complex<long double>> modes_;
};

template <class Real>
double max_error(const sim::DiffusionKernel<Real>& model, const ExactDiffusion& exact, int steps) {
    const auto field = model.field();
    double worst = 0;
    for (int i = 0; i < field.rows(); i += 9)  // 15 x 15 cells spread over the grid
        for (int j = 0; j < field.cols(); j += 9) worst = std::max(worst, std::abs(field(i, j) - exact.at(i, j, steps)));
    return worst;
}

// Percolation's cluster dimension from clusters at sizes up to `largest`:
// mass ~ size^D with D -> 91/48.
struct ClusterFit {
    double slope;
    int kept;  // runs that percolated and entered the fit
};

// The book's route (Fig 7.9): every size from 10 to `largest` once at q, the
// wet cells when the bottom row first gets wet, minus the top row.
ClusterFit book_cluster_fit(int largest, double q, sim::Random& rng) {
    std::vector<double> sizes, cells;
    for (int n = 10; n <= largest; ++n) {
        sim::Percolation model({n, q}, rng);
        if (sim::run_to_bottom_or_fixed_point(model).percolates) {
            sizes.push_back(n);
            cells.push_back(double(model.wet_count() - n));
        }
    }
    return {sim::fit_log_log(sizes, cells).slope, int(sizes.size())};
}

// At p_c: sizes largest / 4, / 2 and largest, `runs` each; the mean mass of
// the whole cluster joined to the top row (run to its fixed point) over the
// runs that span. Only the three largest sizes enter the fit: smaller ones
// carry the corrections to scaling that make a fit from 16 up stall near 1.86.
ClusterFit critical_cluster_fit(int largest, int runs, sim::Random& rng) {
    std::vector<double> sizes, mass;
    int kept = 0;
    for (int n = largest / 4; n <= largest; n *= 2) {
        double total = 0;
        int spanning = 0;
        for (int i = 0; i < runs; ++i) {
            sim::Percolation model({n, exact_p_c}, rng);
            if (sim::run_to_fixed_point(model).percolates) {
                total += double(model.wet_count());
                ++spanning;
            }
        }
        if (spanning == 0) continue;
        sizes.push_back(n);
        mass.push_back(total / spanning);
        kept += spanning;
    }
    return {sim::fit_log_log(sizes, mass).slope, kept};
}

}  // namespace

// (a) Gray-Scott in float against double on tc7-2's run: B's max and RMS difference.
nlohmann::json gray_scott_float_vs_double(Curves& curves) {
    sim::GrayScottParams p;  // tc7-2: n 100, f 0.035, k 0.057
    sim::Random rng(17);
    const sim::GrayScott start(p, rng);
    sim::GrayScottKernel<double> exact(p, start.a(), start.b());
    sim::GrayScottKernel<float> fast(p, start.a(), start.b());
    nlohmann::json rows = nlohmann::json::array();
    Curve curve{"Gray-Scott float32 vs float64 (RMS of B)", "#2171b5", {}};
    int done = 0;
    double t_double = 0, t_float = 0;
    for (int step : {1000, 3000, 7000}) {
        auto t0 = Clock::now();
        exact.step(step - done, 1);
        t_double += seconds_since(t0);
        t0 = Clock::now();
        fast.step(step - done, 1);
        t_float += seconds_since(t0);
        done = step;
        const Difference d = difference(exact.b(), fast.b());
        rows.push_back({{"step", step},
                        {"max_diff_B", d.max},
                        {"rms_diff_B", d.rms},
                        {"seconds_float", t_float},
                        {"seconds_double", t_double}});
        curve.points.push_back({t_float, std::max(d.rms, 1e-300)});
    }
    curves.numerics.push_back(curve);
    return rows;
}

// (b) Diffusion on the torus, float and double, against its exact solution.
nlohmann::json diffusion_vs_exact(Curves& curves) {
    sim::DiffusionParams p;
    p.n = 128;
    p.r = 0.2;
    p.boundary = sim::Boundary::wrap;
    sim::Random rng(5);
    sim::Grid<double> start(p.n, p.n);
    for (std::size_t i = 0; i < start.size(); ++i) start.data()[i] = rng.uniform();
    const ExactDiffusion exact(start, p.r);

    nlohmann::json rows = nlohmann::json::array();
    auto study = [&](auto& model, const char* precision, Curve curve) {
        double elapsed = 0;
        for (int steps : {10, 100, 1000, 10000}) {
            const auto t0 = Clock::now();
            model.step(steps - model.steps(), 1);
            elapsed += seconds_since(t0);
            const double error = max_error(model, exact, steps);
            rows.push_back({{"precision", precision}, {"n", p.n}, {"r", p.r}, {"steps", steps},
                            {"max_error", error}, {"seconds", elapsed}});
            curve.points.push_back({elapsed, std::max(error, 1e-18)});
        }
        curves.numerics.push_back(curve);
    };
    sim::DiffusionKernel<float> single(p, start);
    sim::DiffusionKernel<double> twice(p, start);
    study(single, "float32", {"diffusion float32 vs exact", "#74c476", {}});
    study(twice, "float64", {"diffusion float64 vs exact", "#006d2c", {}});
    return rows;
}

// (c) The percolation threshold: the book's find_critical walk and Newman-Ziff.
nlohmann::json percolation_threshold(Curves& curves) {
    nlohmann::json rows = nlohmann::json::array();
    // One walk's error is a draw that can land near p_c by luck: the curve
    // shows the RMS error over 10 seeds against the time of one walk.
    Curve walk{"p_c: find_critical walk, n = 100 (RMS of 10 walks)", "#e6550d", {}};
    constexpr int walks = 10;
    for (int iterations : {25, 100, 400, 1600}) {
        double squares = 0, estimates = 0;
        const auto t0 = Clock::now();
        for (int seed = 1; seed <= walks; ++seed) {
            sim::Random rng(seed);
            const auto qs = sim::find_critical(100, 0.6, 0.005, iterations, rng);
            const double estimate = std::accumulate(qs.begin(), qs.end(), 0.0) / double(qs.size());
            estimates += estimate;
            squares += (estimate - exact_p_c) * (estimate - exact_p_c);
        }
        const double rms = std::sqrt(squares / walks), t = seconds_since(t0) / walks;
        rows.push_back({{"method", "find_critical walk, n = 100"}, {"iterations", iterations}, {"walks", walks},
                        {"mean_p_c", estimates / walks}, {"rms_error", rms}, {"seconds_per_walk", t}});
        walk.points.push_back({t, rms});
    }
    Curve nz{"p_c: Newman-Ziff, L = 64", "#756bb1", {}};
    for (int samples : {300, 3000, 30000}) {
        sim::Random rng(3);
        const auto t0 = Clock::now();
        const auto e = sim::newman_ziff_threshold(64, samples, rng);
        const double t = seconds_since(t0);
        rows.push_back({{"method", "Newman-Ziff, L = 64"}, {"samples", samples}, {"p_c", e.p_c},
                        {"standard_error", e.standard_error}, {"error", std::abs(e.p_c - exact_p_c)},
                        {"seconds", t}});
        nz.points.push_back({t, std::max(std::abs(e.p_c - exact_p_c), 1e-7)});
    }
    curves.estimators.push_back(walk);
    curves.estimators.push_back(nz);
    return rows;
}

// (d) Fractal dimensions as the size grows: rule 18's cell-count slope (tc7-7)
// against log2 3, and the percolating cluster's (tc7-9) against 91/48.
nlohmann::json fractal_dimensions(Curves& curves) {
    nlohmann::json rule18 = nlohmann::json::array();
    Curve rule_curve{"rule 18 slope vs log2 3", "#636363", {}};
    for (int n : {128, 512, 2048}) {
        const auto t0 = Clock::now();
        const auto counts = sim::count_cells(18, n);
        std::vector<double> steps, cells;
        for (std::size_t i = 0; i < counts.size(); ++i) {
            steps.push_back(double(i + 1));
            cells.push_back(double(counts[i]));
        }
        const double slope = sim::fit_log_log(steps, cells).slope, t = seconds_since(t0);
        const double error = std::abs(slope - std::log2(3.0));
        rule18.push_back({{"n", n}, {"slope", slope}, {"error", error}, {"seconds", t}});
        rule_curve.points.push_back({t, error});
    }

    nlohmann::json cluster = nlohmann::json::array();
    Curve book{"tc7-9 route (q = 0.59, sizes 10..N) vs 91/48", "#d6616b", {}};
    for (int largest : {100, 200, 400, 800}) {
        sim::Random rng(9);
        const auto t0 = Clock::now();
        const ClusterFit fit = book_cluster_fit(largest, 0.59, rng);
        const double t = seconds_since(t0), error = std::abs(fit.slope - cluster_dimension);
        cluster.push_back({{"method", "book: q = 0.59, every size 10..N once, wet cells at test_perc's stop"},
                           {"N", largest}, {"percolating_runs", fit.kept}, {"slope", fit.slope}, {"error", error},
                           {"seconds", t}});
        book.points.push_back({t, error});
    }
    Curve critical{"cluster mass at p_c (N/4, N/2, N; 200 runs each) vs 91/48", "#843c39", {}};
    for (int largest : {64, 128, 256, 512, 1024}) {
        sim::Random rng(48);
        const auto t0 = Clock::now();
        const ClusterFit fit = critical_cluster_fit(largest, 200, rng);
        const double t = seconds_since(t0), error = std::abs(fit.slope - cluster_dimension);
        cluster.push_back({{"method", "p_c: sizes N/4, N/2, N, 200 runs each, mean mass of spanning clusters"},
                           {"N", largest}, {"percolating_runs", fit.kept}, {"slope", fit.slope}, {"error", error},
                           {"seconds", t}});
        critical.points.push_back({t, error});
    }
    curves.estimators.push_back(rule_curve);
    curves.estimators.push_back(book);
    curves.estimators.push_back(critical);
    return {{"rule_18_vs_log2_3", rule18}, {"percolation_cluster_vs_91_48", cluster}};
}

// Stability over a long run: Gray-Scott at n = 64 for `steps` steps with each
// of the book's three (f, k), in double (equal to the figures' model bit for
// bit); every 10,000 steps both fields must be finite and within [0, 1].
nlohmann::json gray_scott_long_run(long long steps) {
    nlohmann::json rows = nlohmann::json::array();
    for (auto [f, k] : {std::pair{0.035, 0.057}, {0.055, 0.062}, {0.039, 0.065}}) {
        sim::GrayScottParams p;
        p.n = 64;
        p.f = f;
        p.k = k;
        sim::Random rng(17);
        const sim::GrayScott start(p, rng);
        sim::GrayScottKernel<double> model(p, start.a(), start.b());
        double lowest = 1, highest = 0;
        long long done = 0, first_bad = -1;
        const auto t0 = Clock::now();
        while (done < steps && first_bad < 0) {
            const int chunk = int(std::min<long long>(10'000, steps - done));
            model.step(chunk, 0);
            done += chunk;
            for (const sim::Grid<double>& field : {model.a(), model.b()})
                for (double v : field.cells()) {
                    if (!std::isfinite(v) || v < 0 || v > 1) first_bad = done;
                    lowest = std::min(lowest, v);
                    highest = std::max(highest, v);
                }
        }
        const double t = seconds_since(t0);
        rows.push_back({{"n", p.n}, {"f", f}, {"k", k}, {"steps", done}, {"checked_every", 10'000},
                        {"min", lowest}, {"max", highest}, {"within_0_1", first_bad < 0},
                        {"first_check_outside", first_bad}, {"seconds", t},
                        {"cell_updates_per_second", double(done) * p.n * p.n / t}});
    }
    return rows;
}

}  // namespace bench
