// The explicit stability bound on a formula's timestep
// (sim/formula/stability.hpp) against the stencils' known eigenvalues:
// forward Euler is stable while timestep * D * |lambda_min| <= 2, Heun
// the same, RK4 to 2.7853 on the negative real axis.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sim/formula/stability.hpp"

using namespace sim::formula;

namespace {

Rule diffusion(const std::string& code, double D, Accuracy accuracy, Integrator integrator) {
    Rule r;
    r.chemicals = 1;
    r.code = code;
    r.parameters = {{"timestep", 0.1}, {"D", D}};
    r.accuracy = accuracy;
    r.integrator = integrator;
    return r;
}

double bound(const Rule& r, int dimensions, double base = 0.0) {
    return stability_bound(r, dimensions, std::vector<double>(static_cast<std::size_t>(r.chemicals), base)).timestep;
}

// RK4's reach along the negative real axis: the root of 1 + z + z^2/2 + z^3/6 + z^4/24 = 1 below 0.
constexpr double rk4_reach = 2.785293563405282;

}  // namespace

TEST_CASE("the stability bound is 2 over the stencil's largest rate, for each integrator", "[formula][stability]") {
    const std::string heat = "delta_a = D * laplacian_a;";
    // 2-D medium (Ready's 9-point (1, 4, -20) / 6): -32/6 at (pi, pi). The example: 0.375.
    CHECK(bound(diffusion(heat, 1, Accuracy::medium, Integrator::euler), 2) == Approx(0.375).epsilon(1e-9));
    CHECK(bound(diffusion(heat, 1, Accuracy::medium, Integrator::heun), 2) == Approx(0.375).epsilon(1e-9));
    CHECK(bound(diffusion(heat, 1, Accuracy::medium, Integrator::rk4), 2) == Approx(rk4_reach * 6 / 32).epsilon(1e-9));
    // 2-D low (5 points): -8; 1-D (1, -2, 1): -4; 1-D high (-1, 16, -30, 16, -1) / 12: -16/3 at pi.
    CHECK(bound(diffusion(heat, 1, Accuracy::low, Integrator::euler), 2) == Approx(0.25).epsilon(1e-9));
    // A timestep that float cannot hold (the formula reads 0.3 as 0.30000001): the bound is still the stencil's.
    {
        Rule r = diffusion(heat, 1, Accuracy::medium, Integrator::euler);
        r.set_parameter("timestep", 0.3);
        CHECK(bound(r, 2, 0.5) == Approx(0.375).epsilon(1e-11));
    }
    CHECK(bound(diffusion(heat, 1, Accuracy::medium, Integrator::euler), 1) == Approx(0.5).epsilon(1e-9));
    CHECK(bound(diffusion(heat, 1, Accuracy::high, Integrator::euler), 1) == Approx(2 * 12.0 / 64).epsilon(1e-9));
    // 3-D (27 points (1, 3, 14, -128) / 30): -184/30 at (pi, pi, pi).
    CHECK(bound(diffusion(heat, 1, Accuracy::medium, Integrator::euler), 3) == Approx(60.0 / 184).epsilon(1e-9));
    // The coefficient and dx scale it: D = 0.2; dx = 0.5 (the Laplacian over dx^2).
    CHECK(bound(diffusion(heat, 0.2, Accuracy::medium, Integrator::euler), 2) == Approx(0.375 / 0.2).epsilon(1e-9));
    Rule fine = diffusion(heat, 1, Accuracy::medium, Integrator::euler);
    fine.parameters.push_back({"dx", 0.5});
    CHECK(bound(fine, 2) == Approx(0.375 / 4).epsilon(1e-9));
}

TEST_CASE("reactions set no bound and Gray-Scott's is its faster chemical's and advection has none under Euler", "[formula][stability]") {
    CHECK(std::isinf(bound(diffusion("delta_a = -D * a * a + 1.0f;", 1, Accuracy::medium, Integrator::euler), 2, 0.5)));
    Rule gs;
    gs.chemicals = 2;
    gs.parameters = {{"timestep", 1.0}, {"D_a", 0.2}, {"D_b", 0.1}, {"F", 0.037}, {"K", 0.06}};
    gs.code = "delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\n"
              "delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;";
    const StabilityBound b = stability_bound(gs, 2, {1.0, 0.25});
    CHECK(b.timestep == Approx(0.375 / 0.2).epsilon(1e-6));
    CHECK(b.chemical == "a");
    CHECK(b.rate_real == Approx(-0.2 * 32 / 6).epsilon(1e-6));
    // Central differences: an imaginary rate, outside forward Euler's region
    // at every timestep; inside RK4's up to 2 sqrt(2) / |rate|.
    const std::string advection = "delta_a = -D * x_gradient_a;";
    CHECK(bound(diffusion(advection, 1, Accuracy::medium, Integrator::euler), 1) == 0);
    CHECK(bound(diffusion(advection, 1, Accuracy::medium, Integrator::rk4), 1) == Approx(2 * std::sqrt(2.0)).epsilon(1e-6));
    // Schroedinger's equation as two real chemicals: each one's change is the
    // other's Laplacian, rates +-i D lambda: none under Euler, RK4 to
    // 2 sqrt(2) / (4 D) in 1-D.
    Rule schroedinger;
    schroedinger.chemicals = 2;
    schroedinger.parameters = {{"timestep", 0.01}, {"D", 0.5}};
    schroedinger.code = "delta_a = -D * laplacian_b;\ndelta_b = D * laplacian_a;";
    CHECK(stability_bound(schroedinger, 1, {0.0, 0.0}).timestep == 0);
    schroedinger.integrator = Integrator::rk4;
    const StabilityBound rk4 = stability_bound(schroedinger, 1, {0.0, 0.0});
    CHECK(rk4.timestep == Approx(2 * std::sqrt(2.0) / 2).epsilon(1e-6));
    CHECK(rk4.rate_real == Approx(0).margin(1e-9));
    CHECK(std::abs(rk4.rate_imaginary) == Approx(2).epsilon(1e-9));
    // With a third chemical, the potential, that no stencil reads (fx-tunnelling's form).
    schroedinger.chemicals = 3;
    schroedinger.code = "delta_a = -D * laplacian_b - c*b;\ndelta_b = D * laplacian_a + c*a;";
    CHECK(stability_bound(schroedinger, 1, {0.0, 0.0, 0.1}).timestep == Approx(std::sqrt(2.0)).epsilon(1e-6));
}
