// Formula models (sim/formula/rule.hpp): the grammar and its refusals, every
// stencil keyword at every accuracy against values worked out by hand, both
// kinds of edges (Ready's and true ones), and tc7-2's model written as a
// formula against figgen's own Gray-Scott.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "sim/formula/run.hpp"
#include "sim/gray_scott.hpp"
#include "sim/random.hpp"

using sim::Grid;
using namespace sim::formula;

namespace {

// a(x, y) = x^2 + 10 y^2 on a width x height grid (row y, column x).
Grid<double> quadratic(int width, int height) {
    Grid<double> g(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) g(y, x) = double(x) * x + 10.0 * y * y;
    return g;
}

Rule one_chemical(const std::string& code) {
    Rule r;
    r.chemicals = 1;
    r.parameters = {{"timestep", 1.0}};
    r.code = code;
    r.double_precision = true;
    return r;
}

// The keyword's value at every cell: delta_a = keyword, one step of
// timestep 1, minus the start.
Grid<double> keyword(const std::string& name, Rule r, const Grid<double>& a) {
    r.code = "delta_a = " + name + ";";
    Run run(r, a.cols(), a.rows(), {a});
    run.step(1, 1);
    Grid<double> after = run.chemical(0);
    for (int y = 0; y < a.rows(); ++y)
        for (int x = 0; x < a.cols(); ++x) after(y, x) -= a(y, x);
    return after;
}

std::string refusal(const std::string& code, int chemicals = 2) {
    Rule r = one_chemical(code);
    r.chemicals = chemicals;
    r.parameters = {{"timestep", 1.0}, {"k", 0.5}};
    try {
        Run run(r, 8, 8, std::vector<Grid<double>>(static_cast<std::size_t>(chemicals), Grid<double>(8, 8, 1.0)));
    } catch (const FormulaError& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("every stencil at every accuracy gives the values worked out by hand", "[formula]") {
    // Inside the grid (3 cells from every edge), on x^2 + 10 y^2: the
    // second derivatives 2 and 20, so every Laplacian is 22 and every
    // higher one 0; a gradient is 2x and 20y; the 5 x 5 Gaussian adds its
    // weights' second moment, 268/273 per unit of curvature; a Sobel
    // filter sums its column (row) of weights times the difference.
    const Grid<double> a = quadratic(16, 16);
    for (Accuracy accuracy : {Accuracy::low, Accuracy::medium, Accuracy::high}) {
        Rule r = one_chemical("");
        r.accuracy = accuracy;
        INFO("accuracy " << static_cast<int>(accuracy));
        const int x = 6, y = 9;  // inside
        CHECK(keyword("laplacian_a", r, a)(y, x) == Approx(22.0).margin(1e-9));
        CHECK(keyword("x_gradient_a", r, a)(y, x) == Approx(2.0 * x).margin(1e-9));
        CHECK(keyword("y_gradient_a", r, a)(y, x) == Approx(20.0 * y).margin(1e-9));
        CHECK(keyword("x_deriv2_a", r, a)(y, x) == Approx(2.0).margin(1e-9));
        CHECK(keyword("y_deriv2_a", r, a)(y, x) == Approx(20.0).margin(1e-9));
        CHECK(keyword("x_deriv3_a", r, a)(y, x) == Approx(0.0).margin(1e-9));
        CHECK(keyword("y_deriv3_a", r, a)(y, x) == Approx(0.0).margin(1e-9));
        CHECK(keyword("z_gradient_a", r, a)(y, x) == Approx(0.0).margin(1e-9));  // one layer: the cell itself
        CHECK(keyword("bilaplacian_a", r, a)(y, x) == Approx(0.0).margin(1e-9));
        CHECK(keyword("trilaplacian_a", r, a)(y, x) == Approx(0.0).margin(1e-9));
        CHECK(keyword("gaussian_a", r, a)(y, x) == Approx(a(y, x) + 11.0 * 268.0 / 273.0).margin(1e-9));
        CHECK(keyword("gradient_mag_squared_a", r, a)(y, x) == Approx(4.0 * x * x + 400.0 * y * y).margin(1e-6));
        // Sobel: the weights 1 2 1 (4 in all) times the difference two cells apart.
        const double north = 10.0 * ((y + 1) * (y + 1) - (y - 1) * (y - 1)), east = double((x + 1) * (x + 1) - (x - 1) * (x - 1));
        CHECK(keyword("sobelN_a", r, a)(y, x) == Approx(4 * north).margin(1e-9));  // 160 y
        CHECK(keyword("sobelS_a", r, a)(y, x) == Approx(-4 * north).margin(1e-9));
        CHECK(keyword("sobelE_a", r, a)(y, x) == Approx(4 * east).margin(1e-9));  // 16 x
        CHECK(keyword("sobelW_a", r, a)(y, x) == Approx(-4 * east).margin(1e-9));
        // The diagonal ones: 2 + 1 on each side, along both axes.
        CHECK(keyword("sobelNE_a", r, a)(y, x) == Approx(3 * (north + east)).margin(1e-9));
        CHECK(keyword("sobelNW_a", r, a)(y, x) == Approx(3 * (north - east)).margin(1e-9));
        CHECK(keyword("sobelSE_a", r, a)(y, x) == Approx(3 * (east - north)).margin(1e-9));
        CHECK(keyword("sobelSW_a", r, a)(y, x) == Approx(-3 * (north + east)).margin(1e-9));
    }
    // dx divides as Ready divides: laplacian by dx^2, gradient by dx.
    Rule r = one_chemical("");
    r.parameters.push_back({"dx", 0.5});
    CHECK(keyword("laplacian_a", r, a)(9, 6) == Approx(22.0 / 0.25));
    CHECK(keyword("x_gradient_a", r, a)(9, 6) == Approx(12.0 / 0.5));
}

TEST_CASE("neighbours and edges follow Ready, or are true edges when asked", "[formula]") {
    const Grid<double> a = quadratic(16, 16);
    Rule r = one_chemical("");
    // Named neighbours: n is y + 1, e is x + 1, a count after the direction.
    CHECK(keyword("a_n", r, a)(5, 5) == a(6, 5));
    CHECK(keyword("a_se2", r, a)(5, 5) == a(4, 7));
    CHECK(keyword("a_n2w3", r, a)(5, 5) == a(7, 2));
    // Ready's clamped edges clamp blocks of four cells in x: west of x = 0
    // is x = 3, east of x = 15 is x = 12; in y each row clamps.
    r.wrap = false;
    CHECK(keyword("x_gradient_a", r, a)(5, 0) == (1.0 - 9.0) / 2);
    CHECK(keyword("x_gradient_a", r, a)(5, 15) == (144.0 - 196.0) / 2);
    CHECK(keyword("a_w2", r, a)(5, 1) == a(5, 3));
    CHECK(keyword("y_gradient_a", r, a)(0, 5) == (10.0 - 0.0) / 2);
    // One cell a block: every cell clamps.
    r.block_x = 1;
    CHECK(keyword("x_gradient_a", r, a)(5, 0) == (1.0 - 0.0) / 2);
    // Wrapped: 16 cells (4 blocks) make a torus.
    r = one_chemical("");
    CHECK(keyword("x_gradient_a", r, a)(5, 0) == (1.0 - 225.0) / 2);
    CHECK(keyword("y_gradient_a", r, a)(0, 5) == (10.0 - 2250.0) / 2);
    // 24 cells (6 blocks, not a power of two): Ready's `& (blocks - 1)`
    // sends x = 24 to block 4, x = 16.
    const Grid<double> wide = quadratic(24, 16);
    CHECK(keyword("x_gradient_a", r, wide)(5, 23) == (256.0 - 484.0) / 2);
    // True edges: a torus of any size, and clamped cells.
    r.ready_edges = false;
    CHECK(keyword("x_gradient_a", r, wide)(5, 23) == (0.0 - 484.0) / 2);
    r.wrap = false;
    CHECK(keyword("x_gradient_a", r, wide)(5, 0) == (1.0 - 0.0) / 2);
    CHECK(keyword("x_gradient_a", r, wide)(5, 23) == (529.0 - 484.0) / 2);
}

TEST_CASE("x_pos and y_pos are the cell's fraction of the grid", "[formula]") {
    const Grid<double> zero(8, 16, 0.0);
    Rule r = one_chemical("");
    CHECK(keyword("x_pos", r, zero)(3, 5) == 5.0 / 16);
    CHECK(keyword("y_pos", r, zero)(3, 5) == 3.0 / 8);
}

// delta_a as `code` computes it, one step of timestep 1 from `a`.
Grid<double> delta(const std::string& code, const Grid<double>& a, Rule r = one_chemical("")) {
    r.code = code;
    Run run(r, a.cols(), a.rows(), {a});
    run.step(1, 1);
    Grid<double> after = run.chemical(0);
    for (int y = 0; y < a.rows(); ++y)
        for (int x = 0; x < a.cols(); ++x) after(y, x) -= a(y, x);
    return after;
}

TEST_CASE("the language: declarations, arrays, loops, if and ?: on the cells", "[formula]") {
    const Grid<double> a = quadratic(8, 8);  // a(y, x) = x^2 + 10 y^2
    // A loop of fixed trips, unrolled; an array with fixed indices.
    CHECK(delta("float4 s[3]; for (int i = 0; i < 3; i++) { s[i] = a * i; } delta_a = s[0] + s[1] + s[2];", a)(2, 3) ==
          3 * a(2, 3));
    // if / else and ?: on each cell's value.
    const Grid<double> branch = delta("if (a > 10.0f) { delta_a = 1.0f; } else { delta_a = -1.0f; }", a);
    CHECK(branch(0, 3) == -1);  // 9
    CHECK(branch(0, 4) == 1);   // 16
    CHECK(branch(1, 0) == -1);  // 10
    const Grid<double> ternary = delta("delta_a = a > 10.0f ? 2.0f : 3.0f;", a);
    CHECK(ternary(0, 3) == 3);
    CHECK(ternary(1, 1) == 2);
    // Nested: only where both hold.
    const Grid<double> nested = delta("if (a > 5.0f) { if (a < 20.0f) delta_a = 7.0f; }", a);
    CHECK(nested(0, 2) == 0);  // 4
    CHECK(nested(0, 3) == 7);  // 9
    CHECK(nested(1, 3) == 7);  // 19
    CHECK(nested(1, 4) == 0);  // 26
    // Compound assignments, ++, ints.
    CHECK(delta("float x = 1.0f; x += 2.0f; x *= 3.0f; x -= 1.0f; x /= 4.0f; int n = 0; n++; n++; delta_a = x + n;",
                a)(0, 0) == 4);
    CHECK(delta("delta_a = 7 / 2 + 7 % 3 + (int)2.9f;", a)(0, 0) == 3 + 1 + 2);
    // Built-ins, OpenCL's definitions.
    const Grid<double> built = delta("delta_a = clamp(a, 4.0f, 9.0f) + step(5.0f, a) + sign(-a) + "
                                     "mix(0.0f, 10.0f, 0.25f) + smoothstep(0.0f, 1.0f, 0.5f) + max(a, 3.0f);",
                                     a);
    CHECK(built(0, 0) == 4 + 0 + 0 + 2.5 + 0.5 + 3);                // a = 0: sign(-0) is -0
    CHECK(built(0, 2) == 4 + 0 - 1 + 2.5 + 0.5 + 4);                // a = 4
    CHECK(built(1, 1) == 9 + 1 - 1 + 2.5 + 0.5 + 11);               // a = 11
    CHECK(delta("delta_a = pow(2.0f, 3.0f) + atan2(0.0f, 1.0f) + fabs(-2.5f);", a)(0, 0) == 10.5);
    // Chemicals can be assigned before the step adds delta.
    CHECK(delta("a = 2.0f * a;", a)(1, 1) == a(1, 1));
    // A comparison is 1 on one cell and -1 on Ready's float4 blocks.
    CHECK(delta("delta_a = (float4)(a > -1.0f);", a)(0, 0) == -1);
    Rule single = one_chemical("");
    single.block_x = 1;
    CHECK(delta("delta_a = (float)(a > -1.0f);", a, single)(0, 0) == 1);
    // Comments of both kinds, and parameters.
    Rule p = one_chemical("");
    p.parameters.push_back({"k", 0.25});
    CHECK(delta("// one\n delta_a = /* two */ k * 4.0f;", a, p)(3, 3) == 1);
}

// What Unstable says when `steps` steps on two threads fail ("" if they do not).
std::string unstable(Run& run, int steps) {
    try {
        run.step(steps, 2);
    } catch (const Unstable& e) {
        return e.what();
    }
    return "";
}

TEST_CASE("a division by zero or a value that is no number stops the run, naming the step and cell", "[formula]") {
    const Grid<double> a = quadratic(8, 8);  // a = 4 at x 2, y 0
    Rule r = one_chemical("delta_a = 1.0f / (a - 4.0f);");
    Run run(r, 8, 8, {a});
    REQUIRE_THROWS_AS(run.step(3, 1), Unstable);
    try {
        run.step(1, 1);
    } catch (const Unstable& e) {
        CHECK_THAT(e.what(), Catch::Equals("step 1, cell (x 2, y 0): division by zero at line 1, column 16 of the formula"));
    }
    CHECK(run.steps() == 0);
    CHECK(run.chemical(0) == a);  // the failed step's input
    // The same division where an if keeps the cell out of it: no error.
    r.code = "if (a != 4.0f) { delta_a = 1.0f / (a - 4.0f); }";
    Run guarded(r, 8, 8, {a});
    CHECK_NOTHROW(guarded.step(1, 1));
    r.code = "delta_a = a != 4.0f ? 1.0f / (a - 4.0f) : 0.0f;";
    Run ternary(r, 8, 8, {a});
    CHECK_NOTHROW(ternary.step(1, 1));
    // NaN on two threads, twenty times: always the first cell in row order.
    r.code = "delta_a = sqrt(30.0f - a);";
    for (int attempt = 0; attempt < 20; ++attempt) {
        Run nan(r, 8, 8, {a});
        CHECK_THAT(unstable(nan, 5), Catch::StartsWith("step 1: chemical a became NaN at cell (x 6, y 0)"));
        CHECK(nan.steps() == 0);
    }
    // After good steps: the step counts on.
    r.code = "delta_a = -1.0f; if (a < 0.5f) delta_a = 1.0f / a;";
    Run later(r, 8, 8, {Grid<double>(8, 8, 2.0)});
    CHECK_THAT(unstable(later, 10), Catch::StartsWith("step 3, cell (x 0, y 0): division by zero"));
    CHECK(later.steps() == 2);
    CHECK(later.chemical(0)(5, 5) == 0.0);
}

TEST_CASE("a formula outside the grammar or its bounds is refused with its line and column", "[formula]") {
    CHECK(refusal("while (a > 0.0f) { a = a - 1.0f; }") == "line 1, column 1: 'while' is not supported in a formula");
    CHECK(refusal("float *p;") == "line 1, column 7: pointers are not supported");
    CHECK(refusal("#include <stdio.h>") == "line 1, column 1: preprocessor lines (#) are not supported");
    CHECK(refusal("delta_a = system(1.0f);") ==
          "line 1, column 11: 'system' is not a function figgen allows (see docs/formulas.md)");
    CHECK(refusal("delta_a = q;") == "line 1, column 11: 'q' is not a chemical, parameter, keyword or variable here");
    CHECK(refusal("for (int i = 0; i < a; i++) delta_a += 1.0f;") ==
          "line 1, column 19: a loop's condition must be known before the run, not vary over the cells");
    CHECK(refusal("float s[2]; s[2] = 1.0f;") == "line 1, column 15: index 2 is outside 's[2]'");
    CHECK(refusal("float s[2]; int i = 0; if (a > 0.5f) i = 1; s[i] = 1.0f;") ==
          "line 1, column 47: an array index must be known before the run, not vary over the cells");
    CHECK(refusal("k = 1.0f;") == "line 1, column 1: 'k' is a parameter of the rule: it cannot be assigned");
    CHECK(refusal("delta_a = a_n * 2.0f\ndelta_b = 1.0f;") == "line 2, column 1: expected ';', found 'delta_b'");
    CHECK(refusal("sin(a);") ==
          "line 1, column 4: a call on its own does nothing: only assignments and declarations are statements");
    CHECK(refusal("delta_a = \"x\";") == "line 1, column 11: strings and characters are not supported");
    CHECK(refusal("delta_a = a.x;") == "line 1, column 12: swizzles and members (.x) are not supported");
    CHECK(refusal("float4 f(float4 x) { return x; }") == "line 1, column 9: functions of the formula's own are not supported");
    CHECK(refusal("delta_a = 1.0f / 0.0f;") == "line 1, column 16: division by zero");
    CHECK(refusal("for (int i = 0; i < 5000; i++) delta_a += 1.0f;") == "line 1, column 1: a loop of more than 4096 trips");
    CHECK(refusal("float a = 1.0f;") == "line 1, column 7: 'a' is already a chemical, parameter or keyword of the rule");
    CHECK(refusal(std::string(70000, ' ')) == "line 1, column 1: the formula has 70000 characters, more than the 65536 allowed");
    std::string deep = "delta_a = ";
    for (int i = 0; i < 100; ++i) deep += "(";
    CHECK_THAT(refusal(deep), Catch::EndsWith("nested more than 64 deep"));
    // The unrolled size is bounded too.
    CHECK_THAT(refusal("for (int i = 0; i < 4000; i++) for (int j = 0; j < 10; j++) delta_a += 1.0f;"),
               Catch::Contains("once its loops are unrolled"));
}

TEST_CASE("tc7-2's model written as a formula in double equals figgen's Gray-Scott", "[formula]") {
    sim::GrayScottParams params;  // the book's: n 100, f 0.035, k 0.057
    sim::Random rng(17);
    const sim::GrayScott start(params, rng);
    sim::GrayScott book(params, start.a(), start.b());
    Rule r;
    r.chemicals = 2;
    r.parameters = {{"timestep", 1.0}, {"ra", 0.5}, {"rb", 0.25}, {"f", 0.035}, {"k", 0.057}};
    // The book's 9-point kernel and order of operations (sim/gray_scott.cpp);
    // its row above is Ready's south.
    r.code = R"(
        double ca = 0.05 * ((a_sw + a_ne) + (a_se + a_nw)) + 0.2 * ((a_s + a_n) + (a_w + a_e)) - a;
        double cb = 0.05 * ((b_sw + b_ne) + (b_se + b_nw)) + 0.2 * ((b_s + b_n) + (b_w + b_e)) - b;
        double reaction = a * (b * b);
        delta_a = (ra * ca - reaction) + f * (1.0 - a);
        delta_b = (rb * cb + reaction) - (f + k) * b;
    )";
    r.double_precision = true;
    r.ready_edges = false;  // 100 cells: Ready's wrap is a torus only for powers of two
    Run formula(r, 100, 100, {start.a(), start.b()});
    for (int i = 0; i < 1000; ++i) book.step();
    formula.step(1000, 2);
    double worst = 0;
    const Grid<double> fa = formula.chemical(0), fb = formula.chemical(1);
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x)
            worst = std::max({worst, std::fabs(fa(y, x) - book.a()(y, x)), std::fabs(fb(y, x) - book.b()(y, x))});
    CHECK(worst <= 1e-12);
    CHECK(formula.steps() == 1000);
}

TEST_CASE("a formula's run is the same bits on any number of threads", "[formula]") {
    sim::Random rng(3);
    Grid<double> a(64, 64), b(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) a(y, x) = 1 - 0.5 * rng.uniform(), b(y, x) = 0.25 * rng.uniform();
    Rule r;
    r.parameters = {{"timestep", 1.0}, {"D_a", 0.2}, {"D_b", 0.1}, {"F", 0.035}, {"K", 0.06}};
    r.code = "delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);\ndelta_b = D_b * laplacian_b + a*b*b - (F+K)*b;";
    Run one(r, 64, 64, {a, b}), three(r, 64, 64, {a, b});
    one.step(50, 1);
    three.step(50, 3);
    CHECK(one.chemical(0) == three.chemical(0));
    CHECK(one.chemical(1) == three.chemical(1));
}
