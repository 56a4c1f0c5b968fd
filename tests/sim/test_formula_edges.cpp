// figgen's own edges for formula rules (Rule::edges) against what is
// known: zero-flux (neumann) edges keep the chemicals' sum to rounding
// for every symmetric stencil; a dirichlet edge's steady state of the
// heat equation is the straight line between the sides' values (every
// second-order stencil is exact on it); a periodic grid of any size is a
// torus (a shifted start gives the shifted end, bit for bit); and the
// ghost rows past a dirichlet side give the same bits in blocks of steps,
// one step at a time, and on any number of threads.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "grid_bits.hpp"
#include "sim/formula/run.hpp"
#include "sim/random.hpp"

using sim::Grid;
using namespace sim::formula;

namespace {

Rule heat(const std::string& code, Accuracy accuracy, const Edges& edges, double timestep, int chemicals = 1) {
    Rule r;
    r.chemicals = chemicals;
    r.code = code;
    r.parameters = {{"timestep", timestep}};
    r.double_precision = true;
    r.block_x = 1;
    r.accuracy = accuracy;
    r.edges = edges;
    return r;
}

Grid<double> noise(int width, int rows, std::uint64_t seed) {
    sim::Random rng(seed);
    Grid<double> g(rows, width);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < width; ++x) g(y, x) = rng.uniform();
    return g;
}

double sum(const Grid<double>& g) {
    double s = 0;
    for (int y = 0; y < g.rows(); ++y)
        for (int x = 0; x < g.cols(); ++x) s += g(y, x);
    return s;
}

const char* accuracy_name(Accuracy a) {
    return a == Accuracy::low ? "low" : a == Accuracy::medium ? "medium" : "high";
}

}  // namespace

TEST_CASE("zero-flux edges keep the sum of every symmetric stencil's run to rounding", "[formula][edges]") {
    struct Case {
        const char* code;
        double timestep;
    };
    // Each stencil, with a timestep inside its bound: the sum moves only by rounding.
    const Case cases[] = {{"delta_a = laplacian_a;", 0.1},
                          {"delta_a = -bilaplacian_a;", 0.01},
                          {"delta_a = trilaplacian_a;", 0.001}};
    for (const Case& c : cases)
        for (Accuracy accuracy : {Accuracy::low, Accuracy::medium, Accuracy::high})
            for (int dims = 1; dims <= 3; ++dims) {
                const int w = 24, h = dims >= 2 ? 20 : 1, d = dims == 3 ? 12 : 1;
                const Grid<double> start = noise(w, h * d, 7);
                Run run(heat(c.code, accuracy, Edges::all(Edge::neumann), c.timestep), w, h, d, {start});
                run.step(200, 2);
                const double before = sum(start), after = sum(run.chemical(0));
                INFO(c.code << " at " << accuracy_name(accuracy) << " accuracy in " << dims << "-D: sum " << before
                             << " became " << after);
                CHECK(std::abs(after - before) <= 1e-12 * before);
                // And it did move: the sum holds because the edges let nothing out, not because nothing ran.
                const Grid<double> end = run.chemical(0);
                CHECK(std::abs(end(0, 0) - start(0, 0)) > 1e-6);
            }
}

TEST_CASE("a dirichlet edge's heat steady state is the straight line between its values", "[formula][edges]") {
    // On n cells centred at x + 1/2, the values 0 and 1 on the sides: u = (x + 1/2) / n,
    // at every accuracy (the 5-point stencil of high accuracy reads two cells past a side).
    const int n = 16;
    for (Accuracy accuracy : {Accuracy::low, Accuracy::medium, Accuracy::high}) {
        Edges e = Edges::all(Edge::dirichlet, {0.0});
        e.side[right].value = {1.0};
        Run run(heat("delta_a = laplacian_a;", accuracy, e, 0.3), n, 1, 1, {Grid<double>(1, n, 0.0)});
        run.step(8000, 1);
        const Grid<double> end = run.chemical(0);
        double most = 0;
        for (int x = 0; x < n; ++x) most = std::max(most, std::abs(end(0, x) - (x + 0.5) / n));
        INFO(accuracy_name(accuracy) << ": largest difference " << most);
        CHECK(most < 1e-12);
    }
}

TEST_CASE("dirichlet sides in 2-D and 3-D with neumann across and a value a chemical", "[formula][edges]") {
    // 2-D: a = 1 on the left, 0 on the right; b = -2 on the left, 2 on the
    // right; the top and bottom let nothing through: a line in x alone.
    const int w = 12, h = 10;
    for (Accuracy accuracy : {Accuracy::low, Accuracy::medium, Accuracy::high})
    for (Integrator integrator : {Integrator::euler, Integrator::rk4}) {
        Edges e = Edges::all(Edge::neumann);
        e.side[left] = {Edge::dirichlet, {1.0, -2.0}};
        e.side[right] = {Edge::dirichlet, {0.0, 2.0}};
        Rule r = heat("delta_a = laplacian_a; delta_b = laplacian_b;", accuracy, e, 0.2, 2);
        r.integrator = integrator;
        Run run(r, w, h, 1, {noise(w, h, 3), noise(w, h, 4)});
        run.step(6000, 2);
        const Grid<double> a = run.chemical(0), b = run.chemical(1);
        double most = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double s = (x + 0.5) / w;
                most = std::max({most, std::abs(a(y, x) - (1 - s)), std::abs(b(y, x) - (-2 + 4 * s))});
            }
        INFO(accuracy_name(accuracy) << ", " << integrator_name(integrator) << ": largest difference " << most);
        CHECK(most < 1e-11);
    }
    // 3-D: back (z = 0) 3, front 5, every other side neumann: a line in z.
    const int d = 8;
    Edges e = Edges::all(Edge::neumann);
    e.side[back] = {Edge::dirichlet, {3.0}};
    e.side[front] = {Edge::dirichlet, {5.0}};
    Run run(heat("delta_a = laplacian_a;", Accuracy::medium, e, 0.2), 6, 5, d, {noise(6, 5 * d, 5)});
    run.step(4000, 2);
    const Grid<double> a = run.chemical(0);
    double most = 0;
    for (int z = 0; z < d; ++z)
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 6; ++x) most = std::max(most, std::abs(a(z * 5 + y, x) - (3 + 2 * (z + 0.5) / d)));
    INFO("3-D: largest difference " << most);
    CHECK(most < 1e-11);
}

TEST_CASE("periodic edges make a torus of any size", "[formula][edges]") {
    // 100 x 36 (no power of two): a start shifted by (7, 5) ends shifted by (7, 5), bit for bit.
    const int w = 100, h = 36;
    const Rule r = heat("delta_a = laplacian_a - 0.3 * x_gradient_a + 0.2 * y_gradient_a - a * a;", Accuracy::high,
                        Edges::all(Edge::periodic), 0.05);
    const Grid<double> start = noise(w, h, 11);
    Grid<double> shifted(h, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) shifted((y + 5) % h, (x + 7) % w) = start(y, x);
    Run one(r, w, h, 1, {start}), other(r, w, h, 1, {shifted});
    one.step(60, 2);
    other.step(60, 2);
    const Grid<double> a = one.chemical(0), b = other.chemical(0);
    Grid<double> moved(h, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) moved((y + 5) % h, (x + 7) % w) = a(y, x);
    CHECK(same_bits(moved, b));
    CHECK(!same_bits(a, start));
}

TEST_CASE("ghost rows give the same bits in blocks of steps and on any number of threads", "[formula][edges]") {
    // Gray-Scott in float on 64 x 300 (its steps go in blocks), a dirichlet
    // top and bottom (ghost rows), neumann left and right.
    Rule r;
    r.chemicals = 2;
    r.code = "delta_a = 0.16 * laplacian_a - a * b * b + 0.035 * (1.0 - a);"
             "delta_b = 0.08 * laplacian_b + a * b * b - 0.095 * b;";
    r.parameters = {{"timestep", 1.0}};
    r.accuracy = Accuracy::high;
    r.block_x = 1;
    Edges e = Edges::all(Edge::neumann);
    e.side[bottom] = {Edge::dirichlet, {1.0, 0.0}};
    e.side[top] = {Edge::dirichlet, {0.5, 0.25}};
    r.edges = e;
    const int w = 64, h = 300;
    Grid<double> a(h, w, 1.0), b = noise(w, h, 9);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) b(y, x) *= 0.25;
    auto run = [&](bool blocks, int threads) {
        use_temporal_blocking(blocks);
        Run x(r, w, h, 1, {a, b});
        x.step(70, threads);
        use_temporal_blocking(true);
        return std::make_pair(x.chemical(0), x.chemical(1));
    };
    {
        Run probe(r, w, h, 1, {a, b});
        CHECK(probe.block_steps() > 1);
    }
    const auto plain = run(false, 1), blocked = run(true, 2), three = run(true, 3);
    CHECK(same_bits(plain.first, blocked.first));
    CHECK(same_bits(plain.second, blocked.second));
    CHECK(same_bits(plain.first, three.first));
    CHECK(same_bits(plain.second, three.second));
    // The ghost rows are read: with neumann edges in their place the bottom row differs.
    r.edges = Edges::all(Edge::neumann);
    const auto neumann = run(false, 1);
    CHECK(plain.first(0, 10) != neumann.first(0, 10));
    CHECK(plain.first(h / 2, 10) == neumann.first(h / 2, 10));
}

TEST_CASE("edges that cannot be are refused before the run", "[formula][edges]") {
    Edges e = Edges::all(Edge::neumann);
    e.side[left].edge = Edge::periodic;
    const Rule one_sided = heat("delta_a = laplacian_a;", Accuracy::low, e, 0.1);
    CHECK_THROWS_WITH(Run(one_sided, 8, 8, 1, {Grid<double>(8, 8, 0.0)}),
                      Catch::Contains("the left side is periodic and the right side neumann"));
    Edges d = Edges::all(Edge::dirichlet, {1.0, 2.0});
    CHECK_THROWS_WITH(Run(heat("delta_a = laplacian_a;", Accuracy::low, d, 0.1), 8, 8, 1, {Grid<double>(8, 8, 0.0)}),
                      Catch::Contains("edge_value of the left side has 2 values, not one a chemical (1)"));
    // The trilaplacian reaches three cells: a grid of two cannot mirror them.
    const Rule wide = heat("delta_a = trilaplacian_a;", Accuracy::low, Edges::all(Edge::neumann), 0.001);
    CHECK_THROWS_WITH(Run(wide, 2, 8, 1, {Grid<double>(8, 2, 0.0)}),
                      Catch::Contains("fewer than its stencils reach past its neumann left side"));
}

TEST_CASE("every stencil keyword reads the mirrored cells: a line through dirichlet sides is exact to the edge", "[formula][edges]") {
    // u = (x + 1/2) / w, the line through 0 on the left side and 1 on the
    // right, neumann at top and bottom: each stencil's value is the line's
    // own, in every cell, those at the sides included (their neighbours
    // past the side are ghosts). One Euler step of timestep 1 gives it.
    const int w = 12, h = 10;
    struct Keyword {
        const char* name;
        double value;
    };
    const Keyword keywords[] = {{"x_gradient_a", 1.0 / w}, {"y_gradient_a", 0},   {"x_deriv2_a", 0},
                                {"x_deriv3_a", 0},         {"y_deriv2_a", 0},     {"laplacian_a", 0},
                                {"bilaplacian_a", 0},      {"trilaplacian_a", 0}, {"sobelE_a", 8.0 / w},
                                {"sobelW_a", -8.0 / w},    {"sobelN_a", 0}};
    Grid<double> line(h, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) line(y, x) = (x + 0.5) / w;
    Edges e = Edges::all(Edge::neumann);
    e.side[left] = {Edge::dirichlet, {0.0}};
    e.side[right] = {Edge::dirichlet, {1.0}};
    for (Accuracy accuracy : {Accuracy::medium, Accuracy::high})
        for (const Keyword& k : keywords) {
            Run run(heat(std::string("delta_a = ") + k.name + ";", accuracy, e, 1.0), w, h, 1, {line});
            run.step(1, 1);
            const Grid<double> end = run.chemical(0);
            double most = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) most = std::max(most, std::abs(end(y, x) - line(y, x) - k.value));
            INFO(k.name << " at " << accuracy_name(accuracy) << ": largest difference " << most);
            CHECK(most < 1e-13);
        }
    // The same line with neumann sides is not the line's: the mirrored cells bend it at the edge.
    Run bent(heat("delta_a = x_gradient_a;", Accuracy::medium, Edges::all(Edge::neumann), 1.0), w, h, 1, {line});
    bent.step(1, 1);
    CHECK(bent.chemical(0)(0, 0) - line(0, 0) == Approx(0.5 / w));  // (u(1) - u(0)) / 2: the mirror of 0 is 0
}
