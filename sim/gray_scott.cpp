#include "sim/gray_scott.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/check.hpp"

namespace sim {
namespace {

// correlate(x, K) at column j of the row `mid`; l and r are the columns
// beside j (wrapped at the edges). Opposite neighbours are paired before
// adding: the order of additions is then the same under every rotation and
// mirror of the square, so a symmetric state stays symmetric bit for bit.
inline double laplacian(const double* up, const double* mid, const double* down, std::ptrdiff_t l,
                        std::ptrdiff_t j, std::ptrdiff_t r) {
    const double corners = (up[l] + down[r]) + (up[r] + down[l]);
    const double edges = (up[j] + down[j]) + (mid[l] + mid[r]);
    return 0.05 * corners + 0.2 * edges - mid[j];
}

struct Rates {
    double ra, rb, f, fk;  // fk = f + k, as the book's (f+k)
};

// Both updates at column j from the old values (l and r are the columns
// beside it), with the book's order of operations: numpy evaluates
// ra*cA - reaction + f*(1-A) left to right, then adds it to A.
inline void update(const double* a_up, const double* a_mid, const double* a_down, const double* b_up,
                   const double* b_mid, const double* b_down, double* next_a, double* next_b, std::ptrdiff_t l,
                   std::ptrdiff_t j, std::ptrdiff_t r, Rates c) {
    const double ca = laplacian(a_up, a_mid, a_down, l, j, r);
    const double cb = laplacian(b_up, b_mid, b_down, l, j, r);
    const double old_a = a_mid[j], old_b = b_mid[j];
    const double reaction = old_a * (old_b * old_b);
    next_a[j] = old_a + ((c.ra * ca - reaction) + c.f * (1.0 - old_a));
    next_b[j] = old_b + ((c.rb * cb + reaction) - c.fk * old_b);
}

// One row of both fields: a and b point at the rows above, at and below it.
// The interior runs without wrapping, then the two end cells; every cell goes
// through the same update(), so no cell of the torus is special. Nothing
// aliases (the outputs are separate grids): __restrict lets the compiler
// vectorize the interior, each lane doing the scalar arithmetic, same bits.
// Kept out of line: once inlined into step(), GCC 12 stops vectorizing it.
[[gnu::noinline]] void update_row(const double* __restrict a_up, const double* __restrict a_mid,
                                  const double* __restrict a_down, const double* __restrict b_up,
                                  const double* __restrict b_mid, const double* __restrict b_down,
                                  double* __restrict next_a, double* __restrict next_b, std::ptrdiff_t n, Rates c) {
    for (std::ptrdiff_t j = 1; j < n - 1; ++j)
        update(a_up, a_mid, a_down, b_up, b_mid, b_down, next_a, next_b, j - 1, j, j + 1, c);
    update(a_up, a_mid, a_down, b_up, b_mid, b_down, next_a, next_b, n - 1, 0, 1, c);
    update(a_up, a_mid, a_down, b_up, b_mid, b_down, next_a, next_b, n - 2, n - 1, 0, c);
}


}  // namespace

void GrayScottParams::validate() const {
    require_integer("n", n, 3, 4096);  // 3 keeps the 3x3 kernel's nine cells distinct on the torus
    // See the stability note in gray_scott.hpp.
    const char* why = "the 9-point diffusion is monotone up to 1, no new extremes, and blows up beyond 1.25";
    require_number("ra", ra, 0.0, 1.0, why);
    require_number("rb", rb, 0.0, 1.0, why);
    require_number("f", f, 0.0, 0.2);
    require_number("k", k, 0.0, 0.2);
    require_number("noise", noise, 0.0, 1.0);
    require_number("island", island, 0.0, 1.0);
}

GrayScott::GrayScott(const GrayScottParams& params, Random& rng) : params_(params) {
    params_.validate();
    const int n = params_.n;
    a_ = Grid<double>(n, n, 1.0);
    b_ = Grid<double>(n, n, 0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) b_(i, j) = params_.noise * rng.uniform();
    // The book's add_island: b[i-r:i+r, j-r:j+r] += height with i = j = n // 2.
    const int r = n / 20, centre = n / 2;
    for (int i = centre - r; i < centre + r; ++i)
        for (int j = centre - r; j < centre + r; ++j) b_(i, j) += params_.island;
    next_a_ = a_;
    next_b_ = b_;
}

GrayScott::GrayScott(const GrayScottParams& params, Grid<double> a, Grid<double> b) : params_(params) {
    params_.validate();
    require_square_field("A", a, params_.n);
    require_square_field("B", b, params_.n);
    a_ = std::move(a);
    b_ = std::move(b);
    next_a_ = a_;
    next_b_ = b_;
}

void GrayScott::step() {
    const int n = params_.n;
    const Rates rates{params_.ra, params_.rb, params_.f, params_.f + params_.k};
    const double* a = a_.data();
    const double* b = b_.data();
    for (int i = 0; i < n; ++i) {
        const std::size_t up = static_cast<std::size_t>(i == 0 ? n - 1 : i - 1) * n;
        const std::size_t mid = static_cast<std::size_t>(i) * n;
        const std::size_t down = static_cast<std::size_t>(i == n - 1 ? 0 : i + 1) * n;
        update_row(a + up, a + mid, a + down, b + up, b + mid, b + down, next_a_.data() + mid, next_b_.data() + mid, n,
                   rates);
    }
    std::swap(a_, next_a_);
    std::swap(b_, next_b_);
    ++steps_;
}

}  // namespace sim
