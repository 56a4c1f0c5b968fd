// Ready's OpenCL arithmetic (Rule::fused_multiply_add): inside one
// expression, a * b + c rounds once, as clang contracts it for pocl; a
// product stored in a variable first does not. Each case against std::fma
// in float on the same values.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "sim/formula/run.hpp"

using namespace sim::formula;
using sim::Grid;

namespace {

// b after one step from 0 with timestep 1: delta_b itself (0 + 1 * delta_b
// is delta_b exactly), for every cell of a 16 x 1 grid whose a, c and d
// hold values whose products round.
struct Cells {
    std::vector<float> a, c, d;
};

Cells cells() {
    Cells v;
    for (int i = 0; i < 16; ++i) {
        v.a.push_back(1.0f + 0.1234567f * static_cast<float>(i) + 1e-3f / 3);
        v.c.push_back(0.7f - 0.0531f * static_cast<float>(i * i % 7));
        v.d.push_back(-1.3f + 0.0777f * static_cast<float>(i));
    }
    return v;
}

std::vector<float> run_delta(const std::string& delta_b, bool fused) {
    Rule r;
    r.chemicals = 4;
    r.code = "delta_b = " + delta_b + ";";
    r.parameters = {{"timestep", 1.0}, {"k", 0.3}};
    r.block_x = 1;
    r.ready_edges = false;
    r.fused_multiply_add = fused;
    const Cells v = cells();
    Grid<double> a(1, 16), b(1, 16, 0.0), c(1, 16), d(1, 16);
    for (int i = 0; i < 16; ++i) a(0, i) = v.a[i], c(0, i) = v.c[i], d(0, i) = v.d[i];
    Run run(r, 16, 1, {a, b, c, d});
    run.step(1, 1);
    const Grid<double> out = run.chemical(1);
    std::vector<float> result;
    for (int i = 0; i < 16; ++i) result.push_back(static_cast<float>(out(0, i)));
    return result;
}

template <class F>
void check_cells(const std::vector<float>& got, F expected) {
    const Cells v = cells();
    int rounded_differently = 0;
    for (int i = 0; i < 16; ++i) {
        const float want = expected(v.a[i], v.c[i], v.d[i]);
        INFO("cell " << i);
        CHECK(got[i] == want);
    }
    (void)rounded_differently;
}

}  // namespace

TEST_CASE("a product and the sum it meets in one expression round once, as clang contracts them", "[formula]") {
    const float k = 0.3f;
    check_cells(run_delta("a*c + d", true), [](float a, float c, float d) { return std::fma(a, c, d); });
    check_cells(run_delta("d + a*c", true), [](float a, float c, float d) { return std::fma(a, c, d); });
    check_cells(run_delta("a*c - d", true), [](float a, float c, float d) { return std::fma(a, c, -d); });
    check_cells(run_delta("d - a*c", true), [](float a, float c, float d) { return std::fma(-a, c, d); });
    check_cells(run_delta("-(a*c) + d", true), [](float a, float c, float d) { return std::fma(-a, c, d); });
    // Both sides products: the left one is fused, the right rounded alone.
    check_cells(run_delta("a*c + d*a", true), [](float a, float c, float d) { return std::fma(a, c, d * a); });
    // A constant factor, and a product of three: its last multiplication is the one fused.
    check_cells(run_delta("k*a + c", true), [k](float a, float c, float) { return std::fma(k, a, c); });
    check_cells(run_delta("a*c*d + a", true), [](float a, float c, float d) { return std::fma(a * c, d, a); });
    // The sum so far meets the next product: ((a*c + d) + c*d) is fma(c, d, fma(a, c, d)).
    check_cells(run_delta("a*c + d + c*d", true),
                [](float a, float c, float d) { return std::fma(c, d, std::fma(a, c, d)); });
}

TEST_CASE("a product stored first, and plain arithmetic, round every operation", "[formula]") {
    check_cells(run_delta("a*c + d", false), [](float a, float c, float d) {
        const float p = a * c;
        return p + d;
    });
    // Across statements: a variable holds the rounded product.
    const auto stored = run_delta("d; float p = a*c; delta_b = p + d", true);
    check_cells(stored, [](float a, float c, float d) {
        const float p = a * c;
        return p + d;
    });
    // The values chosen do round differently with and without the fusion.
    const Cells v = cells();
    int differ = 0;
    for (int i = 0; i < 16; ++i) differ += std::fma(v.a[i], v.c[i], v.d[i]) != v.a[i] * v.c[i] + v.d[i];
    CHECK(differ > 0);
}

TEST_CASE("the forward Euler step is one fused multiply-add in Ready's OpenCL arithmetic", "[formula]") {
    Rule r;
    r.chemicals = 1;
    r.code = "delta_a = a*a;";
    r.parameters = {{"timestep", 0.1}};
    r.block_x = 1;
    r.ready_edges = false;
    const Cells v = cells();
    Grid<double> a(1, 16);
    for (int i = 0; i < 16; ++i) a(0, i) = v.a[i];
    for (bool fused : {true, false}) {
        r.fused_multiply_add = fused;
        Run run(r, 16, 1, {a});
        run.step(1, 1);
        const float dt = 0.1f;
        for (int i = 0; i < 16; ++i) {
            const float delta = v.a[i] * v.a[i];
            const float want = fused ? std::fma(dt, delta, v.a[i]) : v.a[i] + dt * delta;
            CHECK(static_cast<float>(run.chemical(0)(0, i)) == want);
        }
    }
}

TEST_CASE("a stencil's weighted groups meet its sum in one rounding, in Ready's order", "[formula]") {
    // Ready writes the 2-D medium-accuracy Laplacian as
    // (-20 * a + a_nw + a_ne + a_sw + a_se + 4 * (a_n + a_w + a_e + a_s)) / (6 * dx * dx)
    // with its weights in ascending order; clang makes the first product
    // and a_nw one fma, and the last group and the sum another.
    Rule r;
    r.chemicals = 2;
    r.code = "delta_b = laplacian_a;";
    r.parameters = {{"timestep", 1.0}};
    r.block_x = 1;
    r.ready_edges = false;
    r.fused_multiply_add = true;
    const int w = 8, h = 6;
    Grid<double> a(h, w), b(h, w, 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) a(y, x) = static_cast<float>(0.3 + 0.071 * x * x + 0.013 * y * x + 0.1 / (1 + y));
    Run run(r, w, h, {a, b});
    run.step(1, 1);
    auto at = [&](int x, int y) { return static_cast<float>(a((y + h) % h, (x + w) % w)); };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // north is y + 1 in Ready's indexing.
            // Ready's order: rows north to south, columns west to east.
            float sum = std::fma(-20.0f, at(x, y), at(x - 1, y + 1));
            sum = sum + at(x + 1, y + 1);
            sum = sum + at(x - 1, y - 1);
            sum = sum + at(x + 1, y - 1);
            const float group = ((at(x, y + 1) + at(x - 1, y)) + at(x + 1, y)) + at(x, y - 1);
            sum = std::fma(4.0f, group, sum);
            const float want = sum / 6.0f;
            INFO("x " << x << ", y " << y);
            CHECK(static_cast<float>(run.chemical(1)(y, x)) == want);
        }
}

TEST_CASE("a product by one is still a product that a sum fuses with, as clang keeps it", "[formula]") {
    // With D = 1, clang emits fmul(1, a) and fuses it: (1 * a) + (c * d)
    // is fma(1, a, c * d), a + round(c * d) rounded once; not fma(c, d, a).
    Rule r;
    r.chemicals = 4;
    r.code = "delta_b = D * a + c * d;";
    r.parameters = {{"timestep", 1.0}, {"D", 1.0}};
    r.block_x = 1;
    r.ready_edges = false;
    r.fused_multiply_add = true;
    const Cells v = cells();
    Grid<double> a(1, 16), b(1, 16, 0.0), c(1, 16), d(1, 16);
    for (int i = 0; i < 16; ++i) a(0, i) = v.a[i], c(0, i) = v.c[i], d(0, i) = v.d[i];
    Run run(r, 16, 1, {a, b, c, d});
    run.step(1, 1);
    for (int i = 0; i < 16; ++i) CHECK(static_cast<float>(run.chemical(1)(0, i)) == v.a[i] + v.c[i] * v.d[i]);
}
