// Formula models against answers known in closed form: the Gaussian heat
// kernel (the error of each accuracy's Laplacian falls as dx^2, or dx^4
// for the 1-D high accuracy's five points), and the Fisher-KPP front,
// which travels at 2 sqrt(r D), less Bramson's slow approach.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "sim/formula/run.hpp"

using sim::Grid;
using namespace sim::formula;

namespace {

// The largest difference, over the coarse grid's cells, between the heat
// equation's run from a Gaussian of variance s0 and the heat kernel's
// Gaussian of variance s0 + 2 D t, on a periodic square of side `length`
// cut into cells of side `dx` (`dims` dimensions), by RK4 with a timestep
// small enough that the error is the Laplacian's.
double heat_kernel_error(int dims, Accuracy accuracy, double dx) {
    const double length = 48, s0 = 9, t = 8, D = 1;
    const int n = static_cast<int>(std::lround(length / dx));
    Rule r;
    r.chemicals = 1;
    r.code = "delta_a = D * laplacian_a;";
    const double timestep = 0.05 * dx * dx;
    const int steps = static_cast<int>(std::lround(t / timestep));
    r.parameters = {{"timestep", timestep}, {"D", D}, {"dx", dx}};
    r.double_precision = true;
    r.block_x = 1;
    r.accuracy = accuracy;
    r.integrator = Integrator::rk4;
    r.edges = Edges::all(Edge::periodic);
    const int h = dims == 2 ? n : 1;
    // The cell (x, y) is centred at (x dx, y dx); the Gaussian at the middle.
    // With its images a period or two away: the heat kernel of the torus.
    auto gaussian = [&](double variance, int x, int y) {
        double sum = 0;
        for (int i = -2; i <= 2; ++i)
            for (int j = dims == 2 ? -2 : 0; j <= (dims == 2 ? 2 : 0); ++j) {
                const double cx = (x - n / 2) * dx + i * length, cy = dims == 2 ? (y - n / 2) * dx + j * length : 0;
                sum += std::exp(-(cx * cx + cy * cy) / (2 * variance));
            }
        return std::pow(s0 / variance, dims / 2.0) * sum;
    };
    Grid<double> start(h, n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < n; ++x) start(y, x) = gaussian(s0, x, y);
    Run run(r, n, h, 1, {start});
    run.step(steps, 2);
    const Grid<double> end = run.chemical(0);
    const double variance = s0 + 2 * D * steps * timestep;
    double most = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < n; ++x) most = std::max(most, std::abs(end(y, x) - gaussian(variance, x, y)));
    return most;
}

}  // namespace

TEST_CASE("the heat kernel: each accuracy's Laplacian converges at its order in space", "[formula][known]") {
    struct Case {
        int dims;
        Accuracy accuracy;
        const char* name;
        double order;  // the stencil's: its symbol is -k^2 + O(dx^order k^(order + 2))
    };
    // Ready's 2-D high accuracy (5 x 5, over 60) is of fourth order too.
    const Case cases[] = {{1, Accuracy::low, "1-D low", 2},       {1, Accuracy::high, "1-D high", 4},
                          {2, Accuracy::low, "2-D low", 2},       {2, Accuracy::medium, "2-D medium", 2},
                          {2, Accuracy::high, "2-D high", 4}};
    for (const Case& c : cases) {
        const double coarse = heat_kernel_error(c.dims, c.accuracy, 1.0), fine = heat_kernel_error(c.dims, c.accuracy, 0.5);
        const double observed = std::log2(coarse / fine);
        INFO(c.name << ": error " << coarse << " at dx = 1, " << fine << " at dx = 1/2: order " << observed);
        CHECK(std::abs(observed - c.order) < 0.15);
        // And the answer is near: within 1% of the peak at dx = 1.
        CHECK(coarse < 0.01);
    }
}

TEST_CASE("the Fisher-KPP front travels at 2 sqrt(r D)", "[formula][known]") {
    // u_t = D u_xx + r u (1 - u), 1-D, zero-flux edges, dx a quarter of the
    // front's decay length sqrt(D / r), RK4. From a
    // step the front (u = 1/2) is at c t - 3 / (2 l) ln t + constant, with
    // c = 2 sqrt(r D) and l = sqrt(r / D) (Bramson): between t = 100 and
    // 200 its mean speed is c - 3 ln 2 / (200 l), 0.26% short of c for
    // r = D = 1. Within 1% of c; within 0.5% of Bramson's.
    for (const auto& [r_, D] : {std::pair{1.0, 1.0}, std::pair{2.0, 0.5}}) {
        const double length = std::sqrt(D / r_), dx = length / 4, timestep = 0.6 * dx * dx / D;  // RK4 reaches 0.696
        const double c = 2 * std::sqrt(r_ * D);
        const int n = static_cast<int>((200 * c + 100 * length) / dx), steps = static_cast<int>(std::lround(100 / timestep));
        Rule rule;
        rule.chemicals = 1;
        rule.code = "delta_a = D * laplacian_a + r * a * (1.0 - a);";
        rule.parameters = {{"timestep", timestep}, {"D", D}, {"r", r_}, {"dx", dx}};
        rule.double_precision = true;
        rule.block_x = 1;
        rule.accuracy = Accuracy::low;
        rule.integrator = Integrator::rk4;
        rule.edges = Edges::all(Edge::neumann);
        Grid<double> start(1, n, 0.0);
        for (int x = 0; x < n / 40; ++x) start(0, x) = 1;
        Run run(rule, n, 1, 1, {start});
        // Where u falls through 1/2, between cells.
        auto front = [&] {
            const Grid<double> u = run.chemical(0);
            for (int x = 1; x < n; ++x)
                if (u(0, x) < 0.5) return (x - 1 + (u(0, x - 1) - 0.5) / (u(0, x - 1) - u(0, x))) * dx;
            return n * dx;
        };
        run.step(steps, 2);
        const double at100 = front();
        run.step(steps, 2);
        const double at200 = front();
        const double speed = (at200 - at100) / 100, expected = 2 * std::sqrt(r_ * D);
        const double bramson = expected - 3 * std::log(2.0) / (200 * std::sqrt(r_ / D));
        INFO("r = " << r_ << ", D = " << D << ": speed " << speed << " against " << expected << ", Bramson's "
                    << bramson);
        CHECK(std::abs(speed / expected - 1) < 0.01);
        CHECK(std::abs(speed / bramson - 1) < 0.005);
        CHECK(at200 < n * dx - 50 * length);  // still far from the far side
    }
}
