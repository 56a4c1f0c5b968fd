// Ready's stencils in 1, 2 and 3 dimensions (sim/formula/stencils.hpp),
// against calculus: each derivative stencil, applied to every monomial
// x^a y^b z^c up to the degree its order of accuracy makes it exact for,
// gives the exact derivative at the origin; every smoothing stencil sums
// to its divisor.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sim/formula/stencils.hpp"

using namespace sim::formula;

namespace {

double factorial(int n) {
    double f = 1;
    for (int i = 2; i <= n; ++i) f *= i;
    return f;
}

// The stencil applied to x^a y^b z^c at the origin, dx = 1.
double applied(const Stencil& s, int a, int b, int c) {
    double sum = 0;
    for (const StencilPoint& p : s.points) sum += p.weight * std::pow(p.x, a) * std::pow(p.y, b) * std::pow(p.z, c);
    return sum / s.divisor;
}

// d^p/dx^p d^q/dy^q d^r/dz^r of x^a y^b z^c at the origin.
double derivative(int p, int q, int r, int a, int b, int c) {
    return p == a && q == b && r == c ? factorial(a) * factorial(b) * factorial(c) : 0.0;
}

// (the Laplacian in `dimensions` dimensions)^n of x^a y^b z^c at the origin.
double laplacian_power(int n, int dimensions, int a, int b, int c) {
    double sum = 0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
            const int k = n - i - j;
            if ((dimensions < 2 && j > 0) || (dimensions < 3 && k > 0)) continue;
            sum += factorial(n) / (factorial(i) * factorial(j) * factorial(k)) *
                   derivative(2 * i, 2 * j, 2 * k, a, b, c);
        }
    return sum;
}

struct Exact {
    int order;                   // of the derivative
    std::function<double(int, int, int)> value;  // of the exact operator on a monomial
};

}  // namespace

TEST_CASE("Ready's stencils in 1, 2 and 3 dimensions are exact on the polynomials their order promises") {
    const std::map<Accuracy, const char*> accuracies = {
        {Accuracy::low, "low"}, {Accuracy::medium, "medium"}, {Accuracy::high, "high"}};
    for (int dimensions = 1; dimensions <= 3; ++dimensions)
        for (const auto& [accuracy, accuracy_name] : accuracies) {
            const std::vector<Stencil> stencils = ready_stencils(accuracy, dimensions);
            REQUIRE(stencils.size() == 21);  // Ready's GetKnownStencils, in its order
            CHECK(stencils[0].label == "x_gradient");
            CHECK(stencils[9].label == "gaussian");
            CHECK(stencils[12].label == "trilaplacian");
            CHECK(stencils[20].label == "sobelSE");
            for (const Stencil& s : stencils) {
                INFO(s.label << " in " << dimensions << "-D at " << accuracy_name << " accuracy");
                for (const StencilPoint& p : s.points) {
                    // Points only along the grid's axes, except the sobel stencils (2-D in Ready in every dimension).
                    if (s.label.rfind("sobel", 0) == 0 || (s.label.size() > 2 && s.label[1] == '_')) continue;
                    if (dimensions < 3) CHECK(p.z == 0);
                    if (dimensions < 2) CHECK(p.y == 0);
                }
                if (s.label == "gaussian") {
                    long long total = 0;
                    for (const StencilPoint& p : s.points) {
                        total += p.weight;
                        CHECK(p.weight > 0);
                    }
                    CHECK(total == s.divisor);
                    continue;
                }
                // The derivative each stencil stands for, and the degree up to
                // which it is exact: two past its order for a second-order
                // stencil, four past at high accuracy where Ready has one.
                std::optional<Exact> exact;
                bool fourth = false;
                const char axis = s.label[0];
                const int p = axis == 'x', q = axis == 'y', r = axis == 'z';
                const auto along = [&](int k) {
                    return Exact{k, [=](int a, int b, int c) { return derivative(k * p, k * q, k * r, a, b, c); }};
                };
                if (s.label.find("_gradient") == 1) exact = along(1), fourth = accuracy == Accuracy::high;
                if (s.label.find("_deriv2") == 1) exact = along(2), fourth = accuracy == Accuracy::high;
                if (s.label.find("_deriv3") == 1) exact = along(3), fourth = accuracy == Accuracy::high;
                const auto power = [&](int n) {
                    return Exact{2 * n, [=](int a, int b, int c) { return laplacian_power(n, dimensions, a, b, c); }};
                };
                if (s.label == "laplacian") exact = power(1), fourth = accuracy == Accuracy::high && dimensions < 3;
                if (s.label == "bilaplacian") exact = power(2);
                if (s.label == "trilaplacian") exact = power(3);
                if (!exact) {  // the sobel stencils: differences, summing to zero
                    long long total = 0;
                    for (const StencilPoint& pt : s.points) total += pt.weight;
                    CHECK(total == 0);
                    continue;
                }
                const int degree = exact->order + (fourth ? 3 : 1);
                for (int a = 0; a <= degree; ++a)
                    for (int b = 0; a + b <= degree; ++b)
                        for (int c = 0; a + b + c <= degree; ++c) {
                            INFO("x^" << a << " y^" << b << " z^" << c);
                            CHECK(applied(s, a, b, c) == Approx(exact->value(a, b, c)).margin(1e-9));
                        }
                // And one degree further it is not exact: the order is no higher.
                bool inexact = false;
                const int next = degree + 1;
                for (int a = 0; a <= next; ++a)
                    for (int b = 0; a + b <= next; ++b) {
                        const int c = next - a - b;
                        if (std::fabs(applied(s, a, b, c) - exact->value(a, b, c)) > 1e-9) inexact = true;
                    }
                CHECK(inexact);
            }
        }
    CHECK_THROWS_AS(ready_stencils(Accuracy::medium, 4), std::invalid_argument);
    CHECK_THROWS_AS(ready_stencils(Accuracy::medium, 0), std::invalid_argument);
}
