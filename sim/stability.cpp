#include "sim/stability.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sim {

double symbol_minimum(const Kernel3& kernel, int n) {
    double lowest = 0;
    for (int p = 0; p < n; ++p)
        for (int q = 0; q < n; ++q) {
            const double x = 2 * M_PI * p / n, y = 2 * M_PI * q / n;
            double s = 0;
            for (int i = -1; i <= 1; ++i)
                for (int j = -1; j <= 1; ++j) s += kernel[(i + 1) * 3 + (j + 1)] * std::cos(i * x + j * y);
            lowest = std::min(lowest, s);
        }
    return lowest;
}

double stability_bound(const Kernel3& kernel, int n) { return 2.0 / -symbol_minimum(kernel, n); }

double amplification(const Kernel3& kernel, double r, int n, int steps) {
    std::vector<double> a(static_cast<std::size_t>(n) * n), next(a.size());
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            a[i * n + j] = ((i + j) % 2 ? 1.0 : -1.0) + std::sin(2 * M_PI * i / n) * std::cos(2 * M_PI * j / n);
    auto largest = [](const std::vector<double>& v) {
        double m = 0;
        for (double x : v) m = std::max(m, std::abs(x));
        return m;
    };
    const double start = largest(a);
    for (int s = 0; s < steps; ++s) {
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                double c = 0;
                for (int di = -1; di <= 1; ++di)
                    for (int dj = -1; dj <= 1; ++dj)
                        c += kernel[(di + 1) * 3 + (dj + 1)] * a[((i + di + n) % n) * n + (j + dj + n) % n];
                next[i * n + j] = a[i * n + j] + r * c;
            }
        a.swap(next);
    }
    return largest(a) / start;
}

double empirical_bound(const Kernel3& kernel, double first, double step, int n, int steps) {
    for (double r = first;; r += step)
        if (amplification(kernel, r, n, steps) > 1 + 1e-9 || r > 100) return r;
}

}  // namespace sim
