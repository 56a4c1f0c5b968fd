// The formula's integrators (Rule::integrator) against what is known: a
// Fourier mode of the heat equation on a periodic grid decays, between the
// grid's points, exactly as exp(lambda t) with lambda the stencil's
// eigenvalue, so each integrator's error shows its order in time (forward
// Euler 1, Heun 2, RK4 4); the stages give the same bits on any number of
// threads; a stage that fails stops the run with the step's input kept.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "sim/formula/run.hpp"

using sim::Grid;
using namespace sim::formula;

namespace {

Rule heat(Integrator integrator, Accuracy accuracy = Accuracy::medium) {
    Rule r;
    r.chemicals = 1;
    r.code = "delta_a = D * laplacian_a;";
    r.parameters = {{"timestep", 0.1}, {"D", 0.5}};
    r.double_precision = true;
    r.ready_edges = false;  // a true torus
    r.accuracy = accuracy;
    r.integrator = integrator;
    return r;
}

// cos(kx x + ky y) on a width x height grid.
Grid<double> mode(int width, int height, double kx, double ky) {
    Grid<double> g(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) g(y, x) = std::cos(kx * x + ky * y);
    return g;
}

// The largest difference from exp(lambda T) times the mode after T = 1
// in `steps` steps.
double mode_error(Rule r, int width, int height, double kx, double ky, double lambda, int steps) {
    r.parameters[0].second = 1.0 / steps;
    const Grid<double> start = mode(width, height, kx, ky);
    Run run(r, width, height, {start});
    run.step(steps, 1);
    const Grid<double> end = run.chemical(0);
    double most = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) most = std::max(most, std::abs(end(y, x) - std::exp(lambda) * start(y, x)));
    return most;
}

}  // namespace

TEST_CASE("a Fourier mode's decay shows each integrator's order in time", "[formula][integrators]") {
    // 1-D, the stencil (1, -2, 1): lambda = D (2 cos k - 2).
    const int n = 32;
    const double k = 2 * std::numbers::pi * 8 / n, D = 0.5;
    const double lambda = D * (2 * std::cos(k) - 2);
    struct Expect {
        Integrator integrator;
        double order;
    };
    for (const Expect& e : {Expect{Integrator::euler, 1}, Expect{Integrator::heun, 2}, Expect{Integrator::rk4, 4}}) {
        const double coarse = mode_error(heat(e.integrator), n, 1, k, 0, lambda, 10);
        const double fine = mode_error(heat(e.integrator), n, 1, k, 0, lambda, 20);
        const double finer = mode_error(heat(e.integrator), n, 1, k, 0, lambda, 40);
        INFO("stages " << stages(e.integrator) << ": errors " << coarse << ", " << fine << ", " << finer);
        CHECK(std::log2(coarse / fine) == Approx(e.order).margin(0.15));
        CHECK(std::log2(fine / finer) == Approx(e.order).margin(0.1));
    }
    // 2-D at each accuracy: Ready's 3 x 3 stencils and its 5 x 5 one, each integrator.
    const double kx = 2 * std::numbers::pi * 3 / 16, ky = 2 * std::numbers::pi * 5 / 16;
    const double cx = std::cos(kx), cy = std::cos(ky), cx2 = std::cos(2 * kx), cy2 = std::cos(2 * ky);
    struct Stencil {
        Accuracy accuracy;
        double eigenvalue;
    };
    const Stencil stencils[] = {
        {Accuracy::low, 2 * cx + 2 * cy - 4},
        {Accuracy::medium, (4 * cx * cy + 8 * (cx + cy) - 20) / 6},
        // Ready's 21 points: weights -2 (2, 1), -1 (2, 0), 16 (1, 0), 52... as its symmetric_5x5(0, -2, -1, 16, 52, -252) / 60.
        {Accuracy::high, (-2 * 4 * (std::cos(2 * kx) * cy + cx * std::cos(2 * ky)) - 2 * (cx2 + cy2) +
                          16 * 4 * cx * cy + 52 * 2 * (cx + cy) - 252) / 60},
    };
    for (const Stencil& st : stencils)
        for (const Expect& e : {Expect{Integrator::euler, 1}, Expect{Integrator::heun, 2}, Expect{Integrator::rk4, 4}}) {
            const double l2 = D * st.eigenvalue;
            const double coarse = mode_error(heat(e.integrator, st.accuracy), 16, 16, kx, ky, l2, 16);
            const double fine = mode_error(heat(e.integrator, st.accuracy), 16, 16, kx, ky, l2, 32);
            const double finer = mode_error(heat(e.integrator, st.accuracy), 16, 16, kx, ky, l2, 64);
            INFO(integrator_name(e.integrator) << " at accuracy " << static_cast<int>(st.accuracy) << ": errors "
                                               << coarse << ", " << fine << ", " << finer << ": orders "
                                               << std::log2(coarse / fine) << ", " << std::log2(fine / finer));
            CHECK(std::log2(coarse / fine) == Approx(e.order).margin(0.15));
            CHECK(std::log2(fine / finer) == Approx(e.order).margin(0.1));
        }
}

TEST_CASE("Heun and RK4 give the same bits on any number of threads", "[formula][integrators]") {
    Rule gs;
    gs.chemicals = 2;
    gs.parameters = {{"timestep", 1.0}, {"D_a", 0.2}, {"D_b", 0.1}, {"F", 0.037}, {"K", 0.06}};
    gs.code = "delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\n"
              "delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;";
    Grid<double> a(64, 48, 1.0), b(64, 48, 0.0);
    for (int y = 28; y < 36; ++y)
        for (int x = 20; x < 28; ++x) a(y, x) = 0.5, b(y, x) = 0.25 + 0.01 * ((x * 7 + y * 3) % 5);
    for (Integrator integrator : {Integrator::heun, Integrator::rk4}) {
        gs.integrator = integrator;
        std::vector<std::vector<Grid<double>>> results;
        for (int threads : {1, 2, 3}) {
            Run run(gs, 48, 64, {a, b});
            run.step(37, threads);
            CHECK(run.steps() == 37);
            results.push_back({run.chemical(0), run.chemical(1)});
        }
        for (std::size_t t = 1; t < results.size(); ++t)
            for (int c = 0; c < 2; ++c)
                CHECK(std::memcmp(results[t][c].data(), results[0][c].data(), results[0][c].size() * sizeof(double)) == 0);
        // Not Euler's bits.
        gs.integrator = Integrator::euler;
        Run euler(gs, 48, 64, {a, b});
        euler.step(37, 1);
        CHECK(euler.chemical(1) != results[0][1]);
    }
}

TEST_CASE("a stage that fails stops the run, naming the step, cell and stage", "[formula][integrators]") {
    // a doubles and more each stage until it overflows.
    Rule r;
    r.chemicals = 1;
    r.parameters = {{"timestep", 1.0}};
    r.code = "delta_a = a * a;";
    r.integrator = Integrator::rk4;
    Grid<double> a(8, 8, 0.0);
    a(5, 3) = 3;
    Run run(r, 8, 8, {a});
    std::string what;
    try {
        run.step(20, 2);
    } catch (const Unstable& e) {
        what = e.what();
    }
    CHECK_THAT(what, Catch::Contains("chemical a became infinite at cell (x 3, y 5) (rk4 stage"));
    // The state is the failed step's input: finite, and a grown from 3.
    const Grid<double> kept = run.chemical(0);
    CHECK(std::isfinite(kept(5, 3)));
    CHECK(kept(5, 3) >= 3);
    CHECK(kept(0, 0) == 0);
    CHECK_THAT(what, Catch::StartsWith("step " + std::to_string(run.steps() + 1) + ":"));
}
