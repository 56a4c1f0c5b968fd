#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

#include "sim/diffusion.hpp"
#include "sim/diffusion_kernel.hpp"
#include "sim/random.hpp"

using sim::Diffusion;
using sim::DiffusionKernel;
using sim::DiffusionParams;
using sim::Grid;

namespace {

DiffusionParams wrap_params(int n, double r = 0.1) {
    DiffusionParams p;
    p.n = n;
    p.r = r;
    p.boundary = sim::Boundary::wrap;
    p.block_row = p.block_col = p.block_size = 0;  // the block is unused: every test starts from its own field
    return p;
}

Grid<double> random_field(int n, std::uint64_t seed) {
    sim::Random rng(seed);
    Grid<double> g(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) g(i, j) = rng.uniform();
    return g;
}

double max_abs_diff(const Grid<double>& x, const Grid<double>& y) {
    double m = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) m = std::max(m, std::abs(x.cells()[i] - y.cells()[i]));
    return m;
}

// In long double: a double sum of 4096 cells could itself round by ~1e-9,
// more than the double kernel's own drift bound.
double total(const Grid<double>& g) {
    return static_cast<double>(std::accumulate(g.cells().begin(), g.cells().end(), 0.0L));
}

constexpr double kPi = 3.14159265358979323846;

// One Fourier mode on the torus: 0.5 + 0.25 cos(2 pi (u i + v j) / n). The
// wrapped 5-point Laplacian maps the cosine to itself times
// 2 cos(2 pi u / n) + 2 cos(2 pi v / n) - 4, so each step multiplies its
// amplitude by g = 1 + r (that), and the constant stays: after t steps the
// exact state is 0.5 + 0.25 g^t cos(...).
struct Mode {
    int n, u, v;
    double r;
    double g() const { return 1.0 + r * (2.0 * std::cos(2.0 * kPi * u / n) + 2.0 * std::cos(2.0 * kPi * v / n) - 4.0); }
    Grid<double> at(int t) const {
        const double amplitude = 0.25 * std::pow(g(), t);
        Grid<double> a(n, n);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) a(i, j) = 0.5 + amplitude * std::cos(2.0 * kPi * (u * i + v * j) / n);
        return a;
    }
};

}  // namespace

TEST_CASE("diffusion double kernel equals sim Diffusion with wrap bit for bit", "[diffusion_kernel]") {
    // Same additions in the same order (up, left, right, down), no FMA.
    const DiffusionParams p = wrap_params(100);
    const Grid<double> start = random_field(100, 3);
    Diffusion model(p, start);
    DiffusionKernel<double> kernel(p, start);
    for (int s = 0; s < 100; ++s) model.step();
    kernel.step(100, 2);
    CHECK(kernel.steps() == 100);
    CHECK(kernel.field() == model.field());
}

TEST_CASE("diffusion double kernel equals the model on odd and tiny sizes", "[diffusion_kernel]") {
    // n 1 and 2 (a cell is its own, or its only, neighbour), odd sizes that
    // leave a scalar tail after the vector body, a multiple of 8; r at the
    // stability bound too.
    for (int n : {1, 2, 3, 5, 17, 33, 64}) {
        for (double r : {0.1, 0.25}) {
            const DiffusionParams p = wrap_params(n, r);
            const Grid<double> start = random_field(n, static_cast<std::uint64_t>(n));
            Diffusion model(p, start);
            DiffusionKernel<double> kernel(p, start);
            for (int s = 0; s < 50; ++s) model.step();
            for (int s = 0; s < 50; ++s) kernel.step(1, 1 + s % 2);  // one step at a time, alternating threads
            INFO("n = " << n << ", r = " << r);
            CHECK(kernel.field() == model.field());
        }
    }
}

TEMPLATE_TEST_CASE("diffusion kernel gives the same bits on 1 and 2 threads", "[diffusion_kernel]", float, double) {
    const DiffusionParams p = wrap_params(131);  // odd: uneven row split between threads, a scalar tail in every row
    const Grid<double> start = random_field(131, 5);
    DiffusionKernel<TestType> one(p, start), two(p, start), chunks(p, start), fallback(p, start);
    one.step(300, 1);
    two.step(300, 2);
    for (int s = 0; s < 300; s += 7) chunks.step(std::min(7, 300 - s), 2);  // odd chunks: buffer parity
    fallback.step(300);                                                     // OpenMP's default
    CHECK(one.field() == two.field());
    CHECK(one.field() == chunks.field());
    CHECK(one.field() == fallback.field());
    CHECK(one.field() != DiffusionKernel<TestType>(p, start).field());  // it did move
}

TEST_CASE("diffusion kernels stay within the rounding bound of the exact Fourier solution", "[diffusion_kernel]") {
    // Bound, with unit roundoff u (2^-24 float, 2^-53 double), values in
    // [0.25, 0.75], r = 0.1: the start rounds by <= u/2; a step adds <= 5u
    // summing the neighbours (partial sums up to 3), <= u in neighbours - 4c,
    // <= 2ru from rounding r, <= u/4 in r * (...), <= u/2 in c + ...: with the
    // first two scaled by r, <= 8ru + 0.75u = 1.55u a step. The update is a
    // convex combination (r <= 1/4), so old errors never grow: after t steps
    // the error is <= (0.5 + 1.55 t) u, 9.3e-6 (float) and 1.7e-14 (double)
    // at t = 100. The exact state is computed in double (~1e-16).
    const Mode mode{64, 2, 3, 0.1};
    const int t = 100;
    const DiffusionParams p = wrap_params(mode.n, mode.r);
    DiffusionKernel<float> single(p, mode.at(0));
    DiffusionKernel<double> twice(p, mode.at(0));
    single.step(t, 2);
    twice.step(t, 2);
    const Grid<double> exact = mode.at(t);
    const double float_error = max_abs_diff(single.field(), exact), double_error = max_abs_diff(twice.field(), exact);
    const double bound = (0.5 + 1.55 * t) * std::numeric_limits<float>::epsilon() / 2;
    INFO("g = " << mode.g() << ", g^t = " << std::pow(mode.g(), t));
    INFO("max float error = " << float_error << ", max double error = " << double_error << ", float bound " << bound);
    CHECK(std::pow(mode.g(), t) < 0.5);  // the mode really decayed, so the test sees the dynamics
    CHECK(float_error < bound);
    CHECK(float_error < 1e-5);
    CHECK(float_error > 0.0);  // it really runs in float
    CHECK(double_error < 1e-12);
}

TEMPLATE_TEST_CASE("diffusion kernel conserves mass up to rounding", "[diffusion_kernel]", float, double) {
    // The weights sum to 1, so on the torus the sum stays put in exact
    // arithmetic. Each cell update rounds by at most 1.45u for values in
    // [0, 1] and r = 0.1 (as the bound above: 5u + 2u in the neighbours and
    // their difference with 4c, scaled by r, + u/4 + u/2; rounding r itself
    // keeps the weights summing to 1), so after t steps the sum moves by at
    // most n^2 t 1.45u: 0.35 (float) and 6.5e-10 (double) for n = 64,
    // t = 500, against a sum of about 2048.
    const int n = 64, t = 500;
    const DiffusionParams p = wrap_params(n);
    DiffusionKernel<TestType> kernel(p, random_field(n, 11));
    const double before = total(kernel.field());  // already rounded to TestType
    kernel.step(t, 2);
    const double after = total(kernel.field());
    const double u = std::numeric_limits<TestType>::epsilon() / 2;
    INFO("sum before " << before << ", after " << after << ", moved " << after - before);
    CHECK(std::abs(after - before) <= n * n * t * 1.45 * u);
    CHECK(max_abs_diff(kernel.field(), Grid<double>(n, n, before / (n * n))) < 0.1);  // it did smooth out
}

TEST_CASE("diffusion kernel refuses non-wrap boundaries and bad arguments", "[diffusion_kernel]") {
    DiffusionParams p = wrap_params(8);
    const Grid<double> start(8, 8, 1.0);
    p.boundary = sim::Boundary::zero;
    CHECK_THROWS_WITH(DiffusionKernel<float>(p, start), Catch::Contains("boundary") && Catch::Contains("wrap"));
    CHECK_THROWS_AS(DiffusionKernel<double>(p, start), std::invalid_argument);
    p.boundary = sim::Boundary::wrap;
    CHECK_THROWS_AS(DiffusionKernel<float>(p, Grid<double>(7, 8, 0.0)), std::invalid_argument);
    Grid<double> nan = start;
    nan(3, 3) = std::nan("");
    CHECK_THROWS_AS(DiffusionKernel<double>(p, nan), std::invalid_argument);
    p.r = 0.3;  // beyond the stability bound
    CHECK_THROWS_AS(DiffusionKernel<double>(p, start), std::invalid_argument);
    p.r = 0.1;
    DiffusionKernel<double> kernel(p, start);
    CHECK_THROWS_AS(kernel.step(-1), std::invalid_argument);
    CHECK_THROWS_AS(kernel.step(1, -2), std::invalid_argument);
    kernel.step(0);
    CHECK(kernel.field() == start);
    CHECK(kernel.steps() == 0);
}
