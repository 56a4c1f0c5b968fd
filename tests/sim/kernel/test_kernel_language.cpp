// Kernel rules (sim/kernel/): the OpenCL C of Ready's kernels read by
// figgen's own grammar and run over lanes of work items, against values
// worked out here cell by cell in plain C++.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/kernel/run.hpp"

using Catch::Matchers::Contains;
using sim::Grid;
using sim::kernel::ImageRule;
using sim::kernel::ImageRun;
using sim::kernel::KernelError;

namespace {

ImageRule rule_of(const std::string& text, int chemicals = 1, bool float64 = false, int block_x = 1) {
    ImageRule r;
    r.text = text;
    r.chemicals = chemicals;
    r.float64 = float64;
    r.block[0] = block_x;
    return r;
}

// A start that differs from cell to cell, the same on every run.
Grid<double> ramp(int rows, int cols, double scale = 1.0) {
    Grid<double> g(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) g(r, c) = scale * std::sin(0.37 * c + 1.3 * r) + 0.25 * ((r * 7 + c * 3) % 5);
    return g;
}

Grid<double> run(const ImageRule& rule, int w, int h, const std::vector<Grid<double>>& start, int steps = 1, int threads = 1,
                 int chemical = 0) {
    ImageRun r(rule, w, h, 1, start);
    r.step(steps, threads);
    return r.chemical(chemical);
}

const char* life = R"(
__kernel void rd_compute(__global float *a_in, __global float *a_out)
{
    const int x = get_global_id(0);
    const int y = get_global_id(1);
    const int X = get_global_size(0);
    const int Y = get_global_size(1);
    int n = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            if (dx == 0 && dy == 0) continue;
            n += a_in[((y + dy + Y) % Y) * X + (x + dx + X) % X] > 0.5f ? 1 : 0;
        }
    const float me = a_in[y * X + x];
    a_out[y * X + x] = (n == 3 || (n == 2 && me > 0.5f)) ? 1.0f : 0.0f;
}
)";

}  // namespace

TEST_CASE("A kernel of Conway's Life turns a blinker and moves a glider", "[kernel]") {
    Grid<double> g(10, 12);
    g(4, 5) = g(4, 6) = g(4, 7) = 1;  // a horizontal blinker
    const Grid<double> once = run(rule_of(life), 12, 10, {g}, 1);
    CHECK(once(3, 6) == 1);
    CHECK(once(4, 6) == 1);
    CHECK(once(5, 6) == 1);
    CHECK(once(4, 5) == 0);
    CHECK(once(4, 7) == 0);
    CHECK(run(rule_of(life), 12, 10, {g}, 2) == g);
    // a glider moves one cell down and right in four steps, across the wrap too
    Grid<double> glider(10, 12);
    const int cells[5][2] = {{0, 1}, {1, 2}, {2, 0}, {2, 1}, {2, 2}};
    for (const auto& c : cells) glider(c[0] + 7, c[1] + 9) = 1;
    Grid<double> moved(10, 12);
    for (const auto& c : cells) moved((c[0] + 8) % 10, (c[1] + 10) % 12) = 1;
    CHECK(run(rule_of(life), 12, 10, {glider}, 4) == moved);
}

TEST_CASE("A kernel's integers divide, shift and wrap as OpenCL C's", "[kernel]") {
    const char* text = R"(
__kernel void rd_compute(__global float *a_in, __global float *a_out)
{
    const int x = get_global_id(0);
    int s = x - 7;                  // -7 .. 8
    int q = s / 3, r = s % 3;        // truncation toward zero
    uint u = (uint)s >> 28;          // logical shift of the unsigned
    int sh = s >> 1;                 // arithmetic shift of the signed
    int m = (s & 5) | (s ^ 2) << 2;
    long big = (long)2147483647 + 1; // no wrap in long
    int wrapped = 2147483647 + s * 0 + 1 - 1;
    a_out[x] = (float)(q * 1000 + r * 100) + (float)u * 0.5f + (float)sh * 0.25f + (float)(m % 64) / 1024.0f
             + (float)(big - 2147483647L) * 8.0f + (float)(wrapped == 2147483647);
}
)";
    const Grid<double> out = run(rule_of(text), 16, 1, {Grid<double>(1, 16)});
    for (int x = 0; x < 16; ++x) {
        const int s = x - 7;
        const int q = s / 3, r = s % 3;
        const unsigned u = static_cast<unsigned>(s) >> 28;
        const int sh = s >> 1;
        const int m = (s & 5) | (s ^ 2) << 2;
        const float want = static_cast<float>(q * 1000 + r * 100) + static_cast<float>(u) * 0.5f +
                           static_cast<float>(sh) * 0.25f + static_cast<float>(m % 64) / 1024.0f + 8.0f + 1.0f;
        CHECK(out(0, x) == static_cast<double>(want));
    }
}

TEST_CASE("A kernel's branches, loops, switch and early returns run per work item", "[kernel]") {
    // every lane takes its own path: trip counts, breaks, continues, fall-through, returns
    const char* text = R"(
float f(int k)
{
    if (k % 4 == 3) return -1.0f;   // an early return in a helper
    float acc = 0.0f;
    for (int i = 0; i < k; i++) {
        if (i == 5) break;
        if (i % 2 == 1) continue;
        acc += (float)i;
    }
    return acc;
}

__kernel void rd_compute(__global float *a_in, __global float *a_out)
{
    const int x = get_global_id(0);
    const int y = get_global_id(1);
    const int X = get_global_size(0);
    const int i = y * X + x;
    float v = f(x + y);
    switch ((x + 2 * y) % 5) {
        case 0: v += 100.0f;
        case 1: v += 10.0f; break;      // 0 falls through into 1
        case 3: { v = -v; break; }
        default: v *= 2.0f;
    }
    switch (x % 7 - 3) {              // -3 .. 3: lanes that match no case pass it by
        case 2: v += 0.25f; break;
        case -1: v -= 0.25f; break;
    }
    int k = 0;
    while (k * k < x) k++;
    if (y == 2) { a_out[i] = 7.0f; return; }
    // the right side is not read where the left is false: x - 1 is out of range at x = 0
    if (x > 0 && a_in[i - 1] > 0.5f) v += 0.5f;
    a_out[i] = (x % 3 == 0 ? v : v + 1000.0f * (float)k);
}
)";
    const int X = 37, Y = 5;
    Grid<double> start(Y, X);
    for (int y = 0; y < Y; ++y)
        for (int x = 0; x < X; ++x) start(y, x) = (x * 5 + y) % 3 == 0 ? 1.0 : 0.0;
    const Grid<double> out = run(rule_of(text), X, Y, {start});
    for (int y = 0; y < Y; ++y)
        for (int x = 0; x < X; ++x) {
            const int kk = x + y;
            float v;
            if (kk % 4 == 3) v = -1.0f;
            else {
                float acc = 0;
                for (int i = 0; i < kk; i++) {
                    if (i == 5) break;
                    if (i % 2 == 1) continue;
                    acc += static_cast<float>(i);
                }
                v = acc;
            }
            switch ((x + 2 * y) % 5) {
            case 0: v += 100.0f; [[fallthrough]];
            case 1: v += 10.0f; break;
            case 3: v = -v; break;
            default: v *= 2.0f;
            }
            if (x % 7 - 3 == 2) v += 0.25f;
            if (x % 7 - 3 == -1) v -= 0.25f;
            int k = 0;
            while (k * k < x) k++;
            float want;
            if (y == 2) want = 7.0f;
            else {
                if (x > 0 && start(y, x - 1) > 0.5) v += 0.5f;
                want = x % 3 == 0 ? v : v + 1000.0f * static_cast<float>(k);
            }
            INFO("x " << x << " y " << y);
            CHECK(out(y, x) == static_cast<double>(want));
        }
}

TEST_CASE("A kernel's float4 blocks, swizzles and vector comparisons", "[kernel]") {
    // a 4-cell block a work item, as Ready's block_size_x="4" kernels: each
    // cell takes the mean of its left and right neighbours across blocks
    const char* text = R"(
__constant float half_ = 0.5f;
__kernel void rd_compute(__global float4 *a_in, __global float4 *a_out)
{
    const int bx = get_global_id(0);
    const int BX = get_global_size(0);
    float4 me = a_in[bx];
    float4 left = a_in[(bx - 1 + BX) & (BX - 1)];
    float4 right = a_in[(bx + 1) & (BX - 1)];
    float4 l = (float4)(left.w, me.xyz);
    float4 r = (float4)(me.yzw, right.x);
    float4 mean = (l + r) * half_;
    int4 above = mean > me;                 // -1 where true
    a_out[bx] = select(mean, -mean, above);   // negated where the mean is above
    a_out[bx].y = a_out[bx].y + (float)any(above) * 0.0f;
}
)";
    const int W = 32;
    const Grid<double> start = ramp(1, W);
    const Grid<double> out = run(rule_of(text, 1, false, 4), W, 1, {start});
    for (int x = 0; x < W; ++x) {
        const float l = static_cast<float>(start(0, (x - 1 + W) % W)), r = static_cast<float>(start(0, (x + 1) % W));
        const float me = static_cast<float>(start(0, x));
        const float mean = (l + r) * 0.5f;
        const float want = mean > me ? -mean : mean;
        INFO("x " << x);
        CHECK(out(0, x) == static_cast<double>(want));
    }
}

TEST_CASE("A kernel mixes doubles, floats and built-ins as OpenCL C does", "[kernel]") {
    // 2.0 is a double: (c - a) / (2.0 * dx) is computed in double and rounded to float on return
    const char* text = R"(
#ifdef cl_khr_fp64
    #pragma OPENCL EXTENSION cl_khr_fp64 : enable
#else
    #error "no doubles"
#endif
#define DX 0.1f
float grad(float a, float c, float dx) { return (c - a) / (2.0 * dx); }
__kernel void rd_compute(__global float *a_in, __global float *a_out)
{
    const int x = get_global_id(0);
    const int X = get_global_size(0);
    float a = a_in[(x - 1 + X) % X], c = a_in[(x + 1) % X];
    float g = grad(a, c, DX);
    a_out[x] = g + clamp(a, -0.5f, 0.5f) * exp(-c) + pow(fabs(a), 1.5f) + min(a, c) + hypot(a, c)
             + (float)convert_int_sat_rtz(a * 10.0f) + step(0.0f, a) + sign(c) + fmod(a * 7.0f, 1.0f);
}
)";
    const int W = 24;
    const Grid<double> start = ramp(1, W, 2.0);
    const Grid<double> out = run(rule_of(text), W, 1, {start});
    for (int x = 0; x < W; ++x) {
        const float a = static_cast<float>(start(0, (x - 1 + W) % W)), c = static_cast<float>(start(0, (x + 1) % W));
        const float g = static_cast<float>(static_cast<double>(c - a) / (2.0 * static_cast<double>(0.1f)));
        const float sgn = c > 0 ? 1.0f : c < 0 ? -1.0f : 0.0f;
        float want = g + std::fmin(std::fmax(a, -0.5f), 0.5f) * std::exp(-c);
        want = want + std::pow(std::fabs(a), 1.5f);
        want = want + (c < a ? c : a);
        want = want + std::hypot(a, c);
        want = want + static_cast<float>(static_cast<int>(a * 10.0f));
        want = want + (a < 0.0f ? 0.0f : 1.0f);
        want = want + sgn;
        want = want + std::fmod(a * 7.0f, 1.0f);
        INFO("x " << x);
        CHECK(out(0, x) == static_cast<double>(want));
    }
}

TEST_CASE("A kernel gives the same bits on one, two and three threads", "[kernel]") {
    const char* text = R"(
__kernel void rd_compute(__global float *a_in, __global float *b_in, __global float *a_out, __global float *b_out)
{
    const int x = get_global_id(0), y = get_global_id(1);
    const int X = get_global_size(0), Y = get_global_size(1);
    const int i = X * y + x;
    float s = 0.0f;
    const int reach = 1 + (int)(fabs(b_in[i]) * 3.0f);   // a loop bound of the run
    for (int d = -reach; d <= reach; d++)
        s += a_in[X * ((y + d + Y) % Y) + x] * b_in[X * y + (x + d + X) % X];
    a_out[i] = a_in[i] + 0.01f * sin(s);
    b_out[i] = s > 0.0f ? b_in[i] * 0.99f : b_in[i] + 0.01f * a_in[i];
}
)";
    const int W = 150, H = 47;  // rows longer than a chunk, and chunks of parts of rows
    const std::vector<Grid<double>> start = {ramp(H, W), ramp(H, W, 0.7)};
    ImageRun one(rule_of(text, 2), W, H, 1, start), two(rule_of(text, 2), W, H, 1, start), three(rule_of(text, 2), W, H, 1, start);
    one.step(6, 1);
    two.step(6, 2);
    three.step(6, 3);
    for (int c = 0; c < 2; ++c) {
        CHECK(one.chemical(c) == two.chemical(c));
        CHECK(one.chemical(c) == three.chemical(c));
    }
    CHECK(one.chemical(0) != start[0]);
}

TEST_CASE("A kernel that reads outside a buffer stops with its line, step and work item", "[kernel]") {
    const char* text = "__kernel void rd_compute(__global float *a_in, __global float *a_out)\n"
                       "{\n"
                       "    const int x = get_global_id(0);\n"
                       "    a_out[x] = x == 5 ? a_in[x + 100] : a_in[x];\n"
                       "}\n";
    ImageRun r(rule_of(text), 8, 1, 1, {ramp(1, 8)});
    const Grid<double> before = r.chemical(0);
    REQUIRE_THROWS_WITH(r.step(1, 1), Contains("kernel line 4, step 1, work item (5, 0, 0)") &&
                                          Contains("index 105 of a_in is outside 0 to 7"));
    CHECK(r.chemical(0) == before);  // the failed step's input
    CHECK(r.steps() == 0);
}

TEST_CASE("A kernel's run-time faults stop it with one line", "[kernel]") {
    auto fails = [](const std::string& body, const std::string& what) {
        const std::string text = "__kernel void rd_compute(__global float *a_in, __global float *a_out)\n{\n"
                                 "    const int x = get_global_id(0);\n" + body + "\n}\n";
        ImageRun r(rule_of(text), 8, 1, 1, {ramp(1, 8)});
        REQUIRE_THROWS_WITH(r.step(3, 1), Contains(what));
    };
    fails("    a_out[x] = (float)(7 / (x - 3));", "kernel line 4, step 1, work item (3, 0, 0): an integer division by zero");
    fails("    float k[4] = {1.0f, 2.0f, 3.0f, 4.0f};\n    a_out[x] = k[x];",
          "kernel line 5, step 1, work item (4, 0, 0): index 4 of k is outside 0 to 3");
    fails("    a_out[x] = 1.0f; a_out[0] = 2.0f;", "which work item 0 wrote in this step too");
    fails("    a_out[x] = a_out[(x + 1) % 8];", "an output this work item has not written in this step");
    fails("    float s = 0.0f;\n    for (int i = 0; i >= 0; i++) s += 1.0f;\n    a_out[x] = s;", "more than 4194304 loop iterations");
    fails("    a_out[x] = a_in[x] * 1e30f * 1e30f;", "step 1: chemical a is no longer finite");
}

TEST_CASE("A kernel's text that figgen does not run is one line naming its line", "[kernel]") {
    auto refused = [](const std::string& text, const std::string& what) {
        REQUIRE_THROWS_WITH(ImageRun(rule_of(text), 8, 1, 1, {ramp(1, 8)}), Contains(what));
    };
    const std::string head = "__kernel void rd_compute(__global float *a_in, __global float *a_out)\n{\n";
    refused(head + "    a_out[0] = undefined_thing(1.0f);\n}", "kernel line 3: \"undefined_thing\" is neither");
    refused(head + "    a_in[0] = 1.0f;\n}", "kernel line 3: writes \"a_in\", a buffer the kernel reads");
    refused("float f(float x) { return f(x); }\n" + head + "    a_out[0] = f(1.0f);\n}", "calls itself");
    refused("#error \"nope\"\n" + head + "}", "kernel line 1: #error \"nope\"");
    refused(head + "    barrier(0);\n}", "\"barrier\" is not one of the built-ins");
    refused(head + "    __local float t[4];\n}", "\"__local\" is not part of the OpenCL C");
    refused(head + "    float* p = a_in;\n}", "a pointer variable");
    refused(head + "    a_out[0] = 1.0f\n}", "kernel line 4: expected \";\"");
    refused("__kernel void rd_compute(__global double *a_in, __global double *a_out) {}", "holds double; Ready passes it floats");
    refused("__kernel void other(__global float *a_in, __global float *a_out) {}", "no __kernel function \"rd_compute\"");
    refused(head + "    float k[2][3];\n    a_out[0] = k[1];\n}", "takes 2 indices, not 1");
    refused(head + "    a_out[0] = (float)(1 % 2.0f);\n}", "\"%\" on a float");
}

TEST_CASE("A kernel's a * b + c is one fused multiply-add, as pocl's clang contracts it", "[kernel]") {
    // OpenCL C's FP_CONTRACT ON: within one expression a * b + c rounds once;
    // through a variable it rounds twice. The numbers are chosen so that the two differ.
    const char* text = R"(
__kernel void rd_compute(__global float *a_in, __global float *b_in, __global float *a_out, __global float *b_out)
{
    const int x = get_global_id(0);
    const float a = a_in[x], b = b_in[x];
    float p = a * b;
    a_out[x] = a * b - p;         // fma(a, b, -p): the product's rounding error
    b_out[x] = p - a * b;         // fma(-a, b, p)
}
)";
    Grid<double> a(1, 4), b(1, 4);
    const float as[4] = {1.0f + 0x1p-12f, 3.0f + 0x1p-20f, 0.1f, 1.0f};
    const float bs[4] = {1.0f - 0x1p-12f, 7.0f + 0x1p-21f, 0.3f, 2.0f};
    for (int i = 0; i < 4; ++i) a(0, i) = as[i], b(0, i) = bs[i];
    ImageRun r(rule_of(text, 2), 4, 1, 1, {a, b});
    r.step(1, 1);
    for (int i = 0; i < 4; ++i) {
        const float p = as[i] * bs[i];
        const float err = std::fma(as[i], bs[i], -p);
        INFO("i " << i);
        CHECK(r.chemical(0)(0, i) == static_cast<double>(err));
        CHECK(r.chemical(1)(0, i) == static_cast<double>(std::fma(-as[i], bs[i], p)));
    }
    CHECK(r.chemical(0)(0, 2) != 0.0);  // 0.1f * 0.3f is not a float: its rounding error is not 0
}
