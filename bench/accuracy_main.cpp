// `make bench`, second half: run time against error. Each method is run at
// growing cost and its error measured against an independently known value;
// the results go to bench/results/latest.json and the Pareto plot (time
// against error, log-log, one curve per method) to out/bench-pareto.png.
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numeric>

#include "figures/plot_page.hpp"
#include "render/atomic_file.hpp"
#include "render/colormap.hpp"
#include "render/png_io.hpp"
#include "sim/cell1d.hpp"
#include "sim/diffusion.hpp"
#include "sim/fractal.hpp"
#include "sim/gray_scott.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/percolation.hpp"
#include "sim/percolation_threshold.hpp"
#include "sim/random.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Point {
    double seconds, error;
};

// (a) Gray-Scott in float against double on tc7-2's run: B's max and RMS difference.
nlohmann::json gray_scott_float_vs_double(std::vector<Point>& curve) {
    sim::GrayScottParams p;  // tc7-2: n 100, f 0.035, k 0.057
    sim::Random rng(17);
    const sim::GrayScott start(p, rng);
    sim::GrayScottKernel<double> exact(p, start.a(), start.b());
    sim::GrayScottKernel<float> fast(p, start.a(), start.b());
    nlohmann::json rows = nlohmann::json::array();
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
        const auto bd = exact.b(), bf = fast.b();
        double worst = 0, squares = 0;
        for (std::size_t i = 0; i < bd.size(); ++i) {
            const double d = std::abs(bd.data()[i] - bf.data()[i]);
            worst = std::max(worst, d);
            squares += d * d;
        }
        const double rms = std::sqrt(squares / double(bd.size()));
        rows.push_back({{"step", step},
                        {"max_diff_B", worst},
                        {"rms_diff_B", rms},
                        {"seconds_float", t_float},
                        {"seconds_double", t_double}});
        curve.push_back({t_float, std::max(rms, 1e-300)});
    }
    return rows;
}

// (b) Diffusion on the torus against its exact solution: each Fourier mode is
// multiplied by 1 + r (2 cos x + 2 cos y - 4) a step.
nlohmann::json diffusion_exact(std::vector<Point>& curve) {
    const int n = 32;
    sim::DiffusionParams p;
    p.n = n;
    p.r = 0.2;
    p.boundary = sim::Boundary::wrap;
    sim::Random rng(5);
    sim::Grid<double> start(n, n);
    for (std::size_t i = 0; i < start.size(); ++i) start.data()[i] = rng.uniform();
    // Modes of the start.
    std::vector<std::complex<double>> modes(static_cast<std::size_t>(n) * n);
    for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
            std::complex<double> sum = 0;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    sum += start(i, j) * std::polar(1.0, -2 * M_PI * (double(u) * i + double(v) * j) / n);
            modes[u * n + v] = sum;
        }
    nlohmann::json rows = nlohmann::json::array();
    sim::Diffusion model(p, start);
    int done = 0;
    double elapsed = 0;
    for (int steps : {10, 100, 1000, 10000}) {
        const auto t0 = Clock::now();
        while (done < steps) {
            model.step();
            ++done;
        }
        elapsed += seconds_since(t0);
        double worst = 0;
        for (int i = 0; i < n; i += 7)
            for (int j = 0; j < n; j += 5) {
                std::complex<double> sum = 0;
                for (int u = 0; u < n; ++u)
                    for (int v = 0; v < n; ++v) {
                        const double g =
                            1 + p.r * (2 * std::cos(2 * M_PI * u / n) + 2 * std::cos(2 * M_PI * v / n) - 4);
                        sum += modes[u * n + v] * std::pow(g, steps) *
                               std::polar(1.0, 2 * M_PI * (double(u) * i + double(v) * j) / n);
                    }
                worst = std::max(worst, std::abs(model.field()(i, j) - sum.real() / (n * n)));
            }
        rows.push_back({{"steps", steps}, {"max_error", worst}, {"seconds", elapsed}});
        curve.push_back({elapsed, std::max(worst, 1e-17)});
    }
    return rows;
}

// (c) The percolation threshold: the book's find_critical walk and Newman-Ziff.
nlohmann::json percolation_threshold(std::vector<Point>& walk_curve, std::vector<Point>& nz_curve) {
    const double p_c = 0.59274621;
    nlohmann::json rows = nlohmann::json::array();
    for (int iterations : {25, 100, 400}) {
        sim::Random rng(3);
        const auto t0 = Clock::now();
        double q = 0.6, sum = q;
        for (int i = 0; i < iterations; ++i) {
            sim::PercolationParams pp;
            pp.n = 100;
            pp.q = q;
            sim::Percolation model(pp, rng);
            q += sim::run_to_bottom_or_fixed_point(model).percolates ? -0.005 : 0.005;
            sum += q;
        }
        const double estimate = sum / (iterations + 1), t = seconds_since(t0);
        rows.push_back({{"method", "find_critical walk, n = 100"},
                        {"iterations", iterations},
                        {"p_c", estimate},
                        {"error", std::abs(estimate - p_c)},
                        {"seconds", t}});
        walk_curve.push_back({t, std::abs(estimate - p_c)});
    }
    for (int samples : {300, 3000, 30000}) {
        sim::Random rng(3);
        const auto t0 = Clock::now();
        const auto e = sim::newman_ziff_threshold(64, samples, rng);
        const double t = seconds_since(t0);
        rows.push_back({{"method", "Newman-Ziff, L = 64"},
                        {"samples", samples},
                        {"p_c", e.p_c},
                        {"standard_error", e.standard_error},
                        {"error", std::abs(e.p_c - p_c)},
                        {"seconds", t}});
        nz_curve.push_back({t, std::max(std::abs(e.p_c - p_c), 1e-7)});
    }
    return rows;
}

// (d) Rule 18's cell-count slope against log2 3 as the run grows.
nlohmann::json rule_18_dimension(std::vector<Point>& curve) {
    nlohmann::json rows = nlohmann::json::array();
    for (int n : {128, 512, 2048}) {
        const auto t0 = Clock::now();
        const auto counts = sim::count_cells(18, n);
        std::vector<double> steps, cells;
        for (std::size_t i = 0; i < counts.size(); ++i) {
            steps.push_back(double(i + 1));
            cells.push_back(double(counts[i]));
        }
        const double slope = sim::fit_log_log(steps, cells).slope, t = seconds_since(t0);
        rows.push_back({{"n", n}, {"slope", slope}, {"error", std::abs(slope - std::log2(3.0))}, {"seconds", t}});
        curve.push_back({t, std::abs(slope - std::log2(3.0))});
    }
    return rows;
}

render::Series series_of(const std::vector<Point>& points, const std::string& label, const char* colour) {
    std::vector<double> x, y;
    for (const auto& p : points) {
        x.push_back(p.seconds);
        y.push_back(p.error);
    }
    auto s = figures::line_series(x, y, label, glm::vec4(render::parse_colour(colour), 1), 1.8f, false);
    s.marker_size = 7;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const std::filesystem::path results = argc > 1 ? argv[1] : "bench/results";
    const std::filesystem::path figure = argc > 2 ? argv[2] : "out";
    try {
        std::vector<Point> gs, diffusion, walk, nz, rule18;
        nlohmann::json out = {{"gray_scott_float_vs_double", gray_scott_float_vs_double(gs)},
                              {"diffusion_vs_exact", diffusion_exact(diffusion)},
                              {"percolation_threshold", percolation_threshold(walk, nz)},
                              {"rule_18_dimension", rule_18_dimension(rule18)}};
        std::filesystem::create_directories(results);
        std::filesystem::create_directories(figure);
        render::write_file_atomically(results / "latest.json", out.dump(2) + "\n");

        render::Axes axes;
        axes.x_scale = axes.y_scale = render::Scale::log;
        axes.x_label = "run time (s)";
        axes.y_label = "error";
        axes.title = "Run time against error";
        axes.legend = render::Legend::lower_right;
        axes.series = {series_of(gs, "Gray-Scott float32 vs float64 (RMS of B)", "#2171b5"),
                       series_of(diffusion, "diffusion vs exact Fourier solution", "#31a354"),
                       series_of(walk, "p_c: find_critical walk", "#e6550d"),
                       series_of(nz, "p_c: Newman-Ziff, L = 64", "#756bb1"),
                       series_of(rule18, "rule 18 slope vs log2 3", "#636363")};
        render::PlotStyle style;
        render::write_png(figure / "bench-pareto.png", figures::draw_plot_row({axes}, 900, 600, style),
                          {{"Title", "figgen: run time against error"}});
        std::printf("wrote %s and %s\n", (results / "latest.json").c_str(), (figure / "bench-pareto.png").c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "figgen_accuracy: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
