// Formula rules on 1-D and 3-D grids (sim/formula/run.hpp): the stencils of
// the grid's dimensions, the neighbours along z (a_u, a_d), z_pos, the
// edges along z, and Ready's inbuilt Gray-Scott (ready/pattern.cpp writes it
// as a formula) against a transcription of Ready's own loop.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "sim/formula/program.hpp"
#include "sim/formula/run.hpp"

using namespace sim::formula;
using sim::Grid;

namespace {

Rule one_chemical(const std::string& code, bool wrap = true) {
    Rule r;
    r.chemicals = 1;
    r.code = code;
    r.parameters = {{"timestep", 1.0}};
    r.double_precision = true;
    r.block_x = 1;
    r.wrap = wrap;
    r.ready_edges = false;
    return r;
}

// A w x h x d grid (rows z * h + y) of f(x, y, z).
template <class F>
Grid<double> field(int w, int h, int d, F f) {
    Grid<double> g(h * d, w);
    for (int z = 0; z < d; ++z)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) g(z * h + y, x) = f(x, y, z);
    return g;
}

// One step of `code` from `start`, as the change of each cell (timestep 1).
Grid<double> change(const Rule& r, int w, int h, int d, const Grid<double>& start) {
    Run run(r, w, h, d, {start});
    run.step(1, 1);
    Grid<double> after = run.chemical(0);
    for (int i = 0; i < after.rows(); ++i)
        for (int j = 0; j < after.cols(); ++j) after(i, j) -= start(i, j);
    return after;
}

}  // namespace

TEST_CASE("a grid's dimensions are its sides longer than one cell, as Ready counts them", "[formula]") {
    CHECK(dimensionality(256, 1, 1) == 1);
    CHECK(dimensionality(64, 64, 1) == 2);
    CHECK(dimensionality(32, 32, 32) == 3);
    CHECK(dimensionality(32, 1, 32) == 2);
    CHECK(dimensionality(1, 1, 1) == 1);
}

TEST_CASE("the 3-D Laplacian is exact on a quadratic at every accuracy", "[formula]") {
    // laplacian(x^2 + 2 y^2 + 3 z^2) = 2 + 4 + 6 = 12, away from the edges.
    const int w = 12, h = 10, d = 9;
    const Grid<double> start = field(w, h, d, [](int x, int y, int z) { return 1.0 * x * x + 2.0 * y * y + 3.0 * z * z; });
    for (Accuracy a : {Accuracy::low, Accuracy::medium, Accuracy::high}) {
        Rule r = one_chemical("delta_a = laplacian_a;", false);
        r.accuracy = a;
        const Grid<double> got = change(r, w, h, d, start);
        for (int z = 3; z < d - 3; ++z)
            for (int y = 3; y < h - 3; ++y)
                for (int x = 3; x < w - 3; ++x) REQUIRE(got(z * h + y, x) == Approx(12.0).epsilon(1e-12));
    }
}

TEST_CASE("the 1-D Laplacian is the second difference along x", "[formula]") {
    const int w = 32;
    const Grid<double> start = field(w, 1, 1, [](int x, int, int) { return std::sin(0.7 * x) + 0.01 * x * x * x; });
    const Grid<double> got = change(one_chemical("delta_a = laplacian_a;"), w, 1, 1, start);
    for (int x = 0; x < w; ++x) {
        const double west = start(0, (x + w - 1) % w), east = start(0, (x + 1) % w);
        REQUIRE(got(0, x) == Approx(west + east - 2 * start(0, x)).margin(1e-12));
    }
}

TEST_CASE("up and down are z + 1 and z - 1, wrapped or clamped", "[formula]") {
    const int w = 4, h = 3, d = 5;
    const Grid<double> start = field(w, h, d, [](int x, int y, int z) { return 100.0 * z + 10.0 * y + x; });
    const Grid<double> wrapped = change(one_chemical("delta_a = a_u - a;"), w, h, d, start);
    const Grid<double> clamped = change(one_chemical("delta_a = a_d2 - a;", false), w, h, d, start);
    for (int z = 0; z < d; ++z)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                CHECK(wrapped(z * h + y, x) == (z == d - 1 ? -100.0 * (d - 1) : 100.0));
                CHECK(clamped(z * h + y, x) == -100.0 * (z - std::max(0, z - 2)));
            }
    // A neighbour across y and z at once, and z_pos.
    const Grid<double> both = change(one_chemical("delta_a = a_un - a;", false), w, h, d, start);
    CHECK(both(1 * h + 1, 2) == 110.0);
    const Grid<double> z_pos = change(one_chemical("delta_a = z_pos;"), w, h, d, start);
    for (int z = 0; z < d; ++z) CHECK(z_pos(z * h + 2, 3) == Approx(static_cast<double>(z) / d).margin(1e-12));
}

TEST_CASE("on a 1-D grid the neighbours along y and z are the cell itself", "[formula]") {
    const int w = 8;
    const Grid<double> start = field(w, 1, 1, [](int x, int, int) { return 1.0 + x; });
    for (bool wrap : {true, false}) {
        const Grid<double> got = change(one_chemical("delta_a = a_n + a_s + a_u + a_d - 4*a;", wrap), w, 1, 1, start);
        for (int x = 0; x < w; ++x) CHECK(got(0, x) == 0.0);
    }
}

TEST_CASE("gradient_mag_squared sums the squared gradients of the grid's dimensions", "[formula]") {
    // a = 3x + 5y + 7z: 9 in 1-D, 9 + 25 in 2-D, 9 + 25 + 49 in 3-D, away from the edges.
    auto a = [](int x, int y, int z) { return 3.0 * x + 5.0 * y + 7.0 * z; };
    const Rule r = one_chemical("delta_a = gradient_mag_squared_a;", false);
    CHECK(change(r, 8, 1, 1, field(8, 1, 1, a))(0, 4) == Approx(9.0));
    CHECK(change(r, 8, 8, 1, field(8, 8, 1, a))(4, 4) == Approx(34.0));
    CHECK(change(r, 8, 8, 8, field(8, 8, 8, a))(4 * 8 + 4, 4) == Approx(83.0));
}

TEST_CASE("a step that fails in 3-D names the cell's three coordinates", "[formula]") {
    const int w = 4, h = 3, d = 3;
    const Grid<double> start = field(w, h, d, [](int x, int y, int z) { return x == 1 && y == 2 && z == 2 ? 0.0 : 1.0; });
    Run run(one_chemical("delta_a = 1 / a;"), w, h, d, {start});
    CHECK_THROWS_WITH(run.step(1, 1), Catch::Contains("cell (x 1, y 2, z 2): division by zero"));
}

TEST_CASE("3-D runs give the same bits on any number of threads", "[formula]") {
    Rule r = one_chemical("delta_a = 0.1 * laplacian_a - a*b*b; delta_b = 0.05 * laplacian_b + a*b*b - 0.06*b;");
    r.chemicals = 2;
    r.double_precision = false;
    r.block_x = 4;
    r.ready_edges = true;
    const int w = 16, h = 16, d = 16;
    const Grid<double> a = field(w, h, d, [](int x, int y, int z) { return 1.0 - 0.5 * ((x * 7 + y * 3 + z * 5) % 11 == 0); });
    const Grid<double> b = field(w, h, d, [](int x, int y, int z) { return 0.25 * ((x + 2 * y + 3 * z) % 7 == 0); });
    std::vector<Grid<double>> results;
    for (int threads : {1, 2, 3}) {
        Run run(r, w, h, d, {a, b});
        run.step(20, threads);
        results.push_back(run.chemical(1));
    }
    CHECK(std::memcmp(results[0].data(), results[1].data(), sizeof(double) * results[0].cells().size()) == 0);
    CHECK(std::memcmp(results[0].data(), results[2].data(), sizeof(double) * results[0].cells().size()) == 0);
}

namespace {

// Ready's GrayScottImageRD::InternalUpdate, transcribed: float, the
// seven-point Laplacian in its order, its edges (% or clamped per cell).
void ready_gray_scott(std::vector<float>& a, std::vector<float>& b, int X, int Y, int Z, bool wrap, int steps,
                      float timestep, float D_a, float D_b, float k, float F) {
    std::vector<float> na(a.size()), nb(b.size());
    auto at = [&](int x, int y, int z) { return static_cast<std::size_t>(X * (Y * z + y) + x); };
    auto prev = [&](int v, int n) { return wrap ? (v - 1 + n) % n : std::max(0, v - 1); };
    auto next = [&](int v, int n) { return wrap ? (v + 1) % n : std::min(n - 1, v + 1); };
    for (int s = 0; s < steps; ++s) {
        for (int z = 0; z < Z; ++z)
            for (int y = 0; y < Y; ++y)
                for (int x = 0; x < X; ++x) {
                    const float aval = a[at(x, y, z)], bval = b[at(x, y, z)];
                    const float dda = a[at(x, prev(y, Y), z)] + a[at(x, next(y, Y), z)] + a[at(prev(x, X), y, z)] +
                                      a[at(next(x, X), y, z)] + a[at(x, y, prev(z, Z))] + a[at(x, y, next(z, Z))] -
                                      6 * aval;
                    const float ddb = b[at(x, prev(y, Y), z)] + b[at(x, next(y, Y), z)] + b[at(prev(x, X), y, z)] +
                                      b[at(next(x, X), y, z)] + b[at(x, y, prev(z, Z))] + b[at(x, y, next(z, Z))] -
                                      6 * bval;
                    const float da = D_a * dda - aval * bval * bval + F * (1 - aval);
                    const float db = D_b * ddb + aval * bval * bval - (F + k) * bval;
                    na[at(x, y, z)] = aval + timestep * da;
                    nb[at(x, y, z)] = bval + timestep * db;
                }
        a.swap(na);
        b.swap(nb);
    }
}

}  // namespace

TEST_CASE("Ready's inbuilt Gray-Scott, as a formula, is Ready's loop to the bit in 1, 2 and 3 dimensions", "[formula]") {
    Rule r;
    r.chemicals = 2;
    r.block_x = 1;
    r.ready_edges = false;
    r.code = "float dda = a_s + a_n + a_w + a_e + a_d + a_u - 6*a;\n"
             "float ddb = b_s + b_n + b_w + b_e + b_d + b_u - 6*b;\n"
             "delta_a = D_a*dda - a*b*b + F*(1-a);\n"
             "delta_b = D_b*ddb + a*b*b - (F+k)*b;";
    const float timestep = 1, D_a = 0.2f, D_b = 0.1f, k = 0.062f, F = 0.035f;
    r.parameters = {{"timestep", timestep}, {"D_a", D_a}, {"D_b", D_b}, {"k", k}, {"F", F}};
    struct Size {
        int x, y, z;
    };
    for (const Size size : {Size{64, 1, 1}, Size{24, 20, 1}, Size{12, 10, 8}})
        for (bool wrap : {true, false}) {
            r.wrap = wrap;
            const int n = size.x * size.y * size.z;
            std::vector<float> a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(n));
            for (int i = 0; i < n; ++i) {
                a[i] = 1.0f - 0.5f * ((i * 7919) % 13 < 3);
                b[i] = 0.25f * ((i * 104729) % 17 < 4);
            }
            Grid<double> ga(size.y * size.z, size.x), gb(size.y * size.z, size.x);
            for (int i = 0; i < n; ++i) ga.data()[i] = a[i], gb.data()[i] = b[i];
            Run run(r, size.x, size.y, size.z, {ga, gb});
            run.step(30, 2);
            ready_gray_scott(a, b, size.x, size.y, size.z, wrap, 30, timestep, D_a, D_b, k, F);
            const Grid<double> fa = run.chemical(0), fb = run.chemical(1);
            int differ = 0;
            for (int i = 0; i < n; ++i) differ += fa.data()[i] != a[i] || fb.data()[i] != b[i];
            INFO(size.x << " x " << size.y << " x " << size.z << (wrap ? ", wrapped" : ", clamped"));
            CHECK(differ == 0);
        }
}
