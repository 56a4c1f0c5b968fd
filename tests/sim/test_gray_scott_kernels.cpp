#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "sim/gray_scott.hpp"
#include "sim/gray_scott_kernels.hpp"
#include "sim/parallel_steps.hpp"
#include "sim/random.hpp"

using sim::GrayScott;
using sim::GrayScottKernel;
using sim::GrayScottParams;
using sim::Grid;

namespace {

// tc7-2's start: n 100, the book's rates, seed 17 (figures/tc7-2.toml).
GrayScott tc7_2_start() {
    GrayScottParams p;
    sim::Random rng(17);
    return GrayScott(p, rng);
}

// A start on any n: the model's own noise and island.
GrayScott start(GrayScottParams p, std::uint64_t seed) {
    sim::Random rng(seed);
    return GrayScott(p, rng);
}

double max_abs_diff(const Grid<double>& x, const Grid<double>& y) {
    double m = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) m = std::max(m, std::abs(x.cells()[i] - y.cells()[i]));
    return m;
}

double total(const Grid<double>& g) {
    return std::accumulate(g.cells().begin(), g.cells().end(), 0.0);
}

}  // namespace

TEST_CASE("gray-scott double kernel equals sim GrayScott bit for bit", "[gs_kernel]") {
    // Same operations in the same order (opposite neighbours paired, the book's
    // order of the update), no FMA: the double kernel gives the same bits.
    GrayScott model = tc7_2_start();
    GrayScottKernel<double> kernel(model.params(), model.a(), model.b());
    for (int s = 0; s < 1000; ++s) model.step();
    kernel.step(1000, 2);
    CHECK(kernel.steps() == 1000);
    CHECK(kernel.a() == model.a());
    CHECK(kernel.b() == model.b());
}

TEST_CASE("gray-scott double kernel equals the model on odd and tiny sizes", "[gs_kernel]") {
    // n 3 (the smallest torus: every cell neighbours every other), odd sizes
    // that leave a scalar tail after the vector body, and a multiple of 8.
    for (int n : {3, 4, 5, 17, 33, 64}) {
        GrayScottParams p;
        p.n = n;
        GrayScott model = start(p, static_cast<std::uint64_t>(n));
        GrayScottKernel<double> kernel(p, model.a(), model.b());
        for (int s = 0; s < 50; ++s) model.step();
        for (int s = 0; s < 50; ++s) kernel.step(1, 1 + s % 2);  // one step at a time, alternating threads
        INFO("n = " << n);
        CHECK(kernel.a() == model.a());
        CHECK(kernel.b() == model.b());
    }
}

TEST_CASE("gray-scott float kernel stays within 1e-4 of the double one after 200 steps", "[gs_kernel]") {
    // tc7-2's start; fields lie in [0, 1]. float rounding (2^-24 relative)
    // accumulates over 200 steps of a pattern-forming system: measured
    // differences are about 4e-6 (A and B), the bound leaves a wide margin.
    const GrayScott model = tc7_2_start();
    GrayScottKernel<double> exact(model.params(), model.a(), model.b());
    GrayScottKernel<float> fast(model.params(), model.a(), model.b());
    exact.step(200, 2);
    fast.step(200, 2);
    const double da = max_abs_diff(fast.a(), exact.a()), db = max_abs_diff(fast.b(), exact.b());
    INFO("max |A_float - A_double| = " << da << ", max |B_float - B_double| = " << db);
    CHECK(da < 1e-4);
    CHECK(db < 1e-4);
    CHECK(da > 0.0);  // it really runs in float
}

TEMPLATE_TEST_CASE("gray-scott kernel gives the same bits on 1 and 2 threads", "[gs_kernel]", float, double) {
    GrayScottParams p;
    p.n = 131;  // odd: uneven row split between threads, a scalar tail in every row
    const GrayScott model = start(p, 5);
    GrayScottKernel<TestType> one(p, model.a(), model.b()), two(p, model.a(), model.b()),
        chunks(p, model.a(), model.b()), fallback(p, model.a(), model.b());
    one.step(300, 1);
    two.step(300, 2);
    for (int s = 0; s < 300; s += 7) chunks.step(std::min(7, 300 - s), 2);  // odd chunks: buffer parity
    fallback.step(300);                                                     // OpenMP's default
    CHECK(one.a() == two.a());
    CHECK(one.b() == two.b());
    CHECK(one.a() == chunks.a());
    CHECK(one.b() == chunks.b());
    CHECK(one.a() == fallback.a());
    CHECK(one.b() == fallback.b());
    CHECK(one.a() != GrayScottKernel<TestType>(p, model.a(), model.b()).a());  // it did move
}

TEST_CASE("gray-scott double kernel conserves A plus B when f and k are 0", "[gs_kernel]") {
    // The kernel's weights sum to 0 and the reaction moves A into B, so with
    // no feed and no removal sum(A + B) stays put, up to rounding.
    GrayScottParams p;
    p.n = 64;
    p.f = 0.0;
    p.k = 0.0;
    const GrayScott model = start(p, 11);
    GrayScottKernel<double> kernel(p, model.a(), model.b());
    const double before = total(kernel.a()) + total(kernel.b());
    kernel.step(500, 2);
    const double after = total(kernel.a()) + total(kernel.b());
    CHECK(std::abs(after - before) <= 1e-12 * before);
    CHECK(total(kernel.b()) > total(model.b()));  // the reaction did run
}

TEST_CASE("gray-scott kernel rejects bad sizes and arguments", "[gs_kernel]") {
    GrayScottParams p;
    p.n = 8;
    const Grid<double> a(8, 8, 1.0), b(8, 8, 0.0), wrong(7, 8, 0.0);
    CHECK_THROWS_AS(GrayScottKernel<float>(p, a, wrong), std::invalid_argument);
    Grid<double> nan = b;
    nan(3, 3) = std::nan("");
    CHECK_THROWS_AS(GrayScottKernel<double>(p, a, nan), std::invalid_argument);
    GrayScottKernel<double> kernel(p, a, b);
    CHECK_THROWS_AS(kernel.step(-1), std::invalid_argument);
    CHECK_THROWS_AS(kernel.step(1, -2), std::invalid_argument);
    kernel.step(0);
    CHECK(kernel.a() == a);
    CHECK(kernel.steps() == 0);
}

TEST_CASE("gray-scott float kernel flushes subnormals and leaves the thread's float mode as it was", "[gs_kernel]") {
    // At n = 256 the empty regions' B decays by about 1 - (f + k) a step:
    // after 1000 steps gradual underflow leaves ~24,000 cells below FLT_MIN
    // (measured without the flush), each costing ~100 cycles an operation.
    GrayScottParams p;
    p.n = 256;
    const GrayScott s = start(p, 17);
    GrayScottKernel<float> fast(p, s.a(), s.b());
    const float tiny = std::numeric_limits<float>::denorm_min();
    volatile float probe = tiny;  // subnormal arithmetic here, before and after
    fast.step(1000, 2);
    long subnormal = 0;
    const Grid<double> b = fast.b();
    for (double v : b.cells()) subnormal += v != 0 && std::abs(v) < std::numeric_limits<float>::min();
    CHECK(subnormal == 0);
    CHECK(probe * 2.0f == 2 * tiny);  // this thread still has gradual underflow
    // The double kernel keeps gradual underflow: still the model's bits.
    GrayScottKernel<double> exact(p, s.a(), s.b());
    GrayScott model = s;
    exact.step(50, 2);
    for (int i = 0; i < 50; ++i) model.step();
    CHECK(exact.b() == model.b());
}

namespace {

// The float update written out cell by cell, the scalar way, in update_row's
// order of operations (no FMA: the tests build with -ffp-contract=off too),
// on a plain torus with subnormals flushed as the kernel flushes them.
void reference_float_step(const GrayScottParams& p, std::vector<float>& a, std::vector<float>& b) {
    const int n = p.n;
    const float ra = float(p.ra), rb = float(p.rb), f = float(p.f), fk = float(p.f + p.k);
    const float corner = 0.05f, edge = 0.2f;
    std::vector<float> na(a.size()), nb(b.size());
    auto at = [n](const std::vector<float>& g, int i, int j) { return g[((i + n) % n) * n + (j + n) % n]; };
    auto laplacian = [&](const std::vector<float>& g, int i, int j) {
        const float corners = (at(g, i - 1, j - 1) + at(g, i + 1, j + 1)) + (at(g, i - 1, j + 1) + at(g, i + 1, j - 1));
        const float edges = (at(g, i - 1, j) + at(g, i + 1, j)) + (at(g, i, j - 1) + at(g, i, j + 1));
        return corner * corners + edge * edges - at(g, i, j);
    };
    const sim::SubnormalsFlushed flushed;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const float ca = laplacian(a, i, j), cb = laplacian(b, i, j), old_a = a[i * n + j], old_b = b[i * n + j];
            const float reaction = old_a * (old_b * old_b);
            na[i * n + j] = old_a + ((ra * ca - reaction) + f * (1.0f - old_a));
            nb[i * n + j] = old_b + ((rb * cb + reaction) - fk * old_b);
        }
    a.swap(na);
    b.swap(nb);
}

std::vector<float> as_floats(const Grid<double>& g) { return {g.cells().begin(), g.cells().end()}; }

}  // namespace

TEST_CASE("gray-scott float kernel equals a scalar float update bit for bit, in the vector code this CPU runs",
          "[gs_kernel]") {
    // n 16 and 64: whole 16-cell AVX-512 blocks; 17 and 100: a block body
    // and a tail of 1 and 4 cells; 5: tail only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    // This machine's CPU has AVX-512 (lscpu: avx512f): the kernel must run it.
    if (__builtin_cpu_supports("avx512f")) CHECK(std::string(sim::float_kernel_vectors()) == "avx512f");
#endif
    INFO("rows run on: " << sim::float_kernel_vectors());
    for (int n : {5, 16, 17, 64, 100}) {
        GrayScottParams p;
        p.n = n;
        const GrayScott s = start(p, static_cast<std::uint64_t>(n));
        GrayScottKernel<float> fast(p, s.a(), s.b());
        std::vector<float> a = as_floats(s.a()), b = as_floats(s.b());
        for (int step = 0; step < 60; ++step) reference_float_step(p, a, b);
        fast.step(60, 2);
        INFO("n = " << n);
        CHECK(as_floats(fast.a()) == a);
        CHECK(as_floats(fast.b()) == b);
        CHECK(b != as_floats(s.b()));  // it did move
    }
}

TEST_CASE("gray-scott kernel's exact state tests: B at +0, an unchanged step, the health bound", "[gs_kernel]") {
    GrayScottParams p;
    p.n = 8;
    Grid<double> a(8, 8, 1.0), b(8, 8, 0.0);
    GrayScottKernel<float> rest(p, a, b);
    CHECK(rest.b_is_zero());
    CHECK_FALSE(rest.unchanged());  // no step yet: nothing to compare with
    rest.step(1, 1);
    CHECK(rest.unchanged());  // A = 1, B = 0 is the trivial steady state, exactly
    CHECK(rest.within(1.0));
    CHECK_FALSE(rest.within(0.5));

    b(2, 5) = -0.0;  // -0 is not +0: the B rule must not take it
    CHECK_FALSE(GrayScottKernel<float>(p, a, b).b_is_zero());
    b(2, 5) = 1e-30;
    GrayScottKernel<float> moving(p, a, b);
    CHECK_FALSE(moving.b_is_zero());
    moving.step(1, 1);
    CHECK_FALSE(moving.unchanged());  // B diffuses

    a(7, 7) = 11.0;  // beyond the atlas's health bound of 10
    GrayScottKernel<double> loud(p, a, b);
    CHECK_FALSE(loud.within(10.0));
    CHECK(loud.within(11.0));
    CHECK(loud.b_as_stored() == b);
}

TEST_CASE("gray-scott kernel restarted on a new state and rates runs as a new kernel would", "[gs_kernel]") {
    GrayScottParams p;
    p.n = 48;
    const GrayScott first = start(p, 1);
    GrayScottKernel<float> reused(p, first.a(), first.b());
    reused.step(70, 1);
    GrayScottParams q = p;
    q.f = 0.055;
    q.k = 0.062;
    const GrayScott second = start(q, 2);
    reused.restart(q, second.a(), second.b());
    CHECK(reused.steps() == 0);
    CHECK_FALSE(reused.unchanged());  // no step since the restart
    CHECK(reused.b() == GrayScottKernel<float>(q, second.a(), second.b()).b());
    GrayScottKernel<float> fresh(q, second.a(), second.b());
    reused.step(101, 2);  // odd: the other buffer pair holds the state
    fresh.step(101, 2);
    CHECK(reused.a() == fresh.a());
    CHECK(reused.b() == fresh.b());
    CHECK(reused.params().f == 0.055);
    GrayScottParams r = p;  // a new size: new buffers
    r.n = 20;
    const GrayScott third = start(r, 3);
    reused.restart(r, third.a(), third.b());
    reused.step(10, 1);
    GrayScottKernel<float> small(r, third.a(), third.b());
    small.step(10, 1);
    CHECK(reused.b() == small.b());
    CHECK_THROWS_AS(reused.restart(r, first.a(), third.b()), std::invalid_argument);  // 48 x 48 A for n = 20
}
