#include "render/ticks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace render {
namespace {

const char* const minus_sign = "\u2212";  // matplotlib's axes.unicode_minus

void require_finite(double lo, double hi, const char* what) {
    if (!std::isfinite(lo) || !std::isfinite(hi))
        throw std::invalid_argument(std::string(what) + ": the range must be finite");
}

// A tick on the edge of the range counts as inside it: matplotlib's
// _interval_contains_close, relative to the range's width.
bool within(double v, double lo, double hi) {
    const double slack = 1e-10 * (hi - lo);
    return v >= lo - slack && v <= hi + slack;
}

// matplotlib's _Edge_integer: floor and ceiling of x / step that forgive
// the rounding error of a step that is not exact in binary.
struct Edge {
    double step, tolerance;
    Edge(double s, double offset) : step(s), tolerance(1e-10) {
        if (offset > 0) tolerance = std::min(0.4999, std::max(1e-10, std::pow(10.0, std::log10(offset / s) - 12)));
    }
    bool close(double ms, double edge) const { return std::abs(ms - edge) < tolerance; }
    double le(double x) const {
        const double d = std::floor(x / step), m = x - d * step;
        return close(m / step, 1) ? d + 1 : d;
    }
    double ge(double x) const {
        const double d = std::floor(x / step), m = x - d * step;
        return close(m / step, 0) ? d : d + 1;
    }
};

// MaxNLocator._raw_ticks with steps 1, 2, 2.5, 5, 10 and min_n_ticks 2.
std::vector<double> raw_linear_ticks(double lo, double hi, int bins) {
    const double span = hi - lo, mean = (hi + lo) / 2;
    // scale_range: an offset when the range is a sliver far from zero.
    const double offset = std::abs(mean) / span < 100 ? 0.0
                          : std::copysign(std::pow(10.0, std::floor(std::log10(std::abs(mean)))), mean);
    const double scale = std::pow(10.0, std::floor(std::log10(span / bins)));
    const double vmin = lo - offset, vmax = hi - offset, raw_step = (vmax - vmin) / bins;
    const std::array<double, 10> extended{0.1, 0.2, 0.25, 0.5, 1, 2, 2.5, 5, 10, 20};
    std::size_t first = 0;
    while (first + 1 < extended.size() && extended[first] * scale < raw_step) ++first;
    std::vector<double> ticks;
    // The smallest nice step not below the raw one, or a smaller one if it leaves fewer than two ticks in view.
    for (std::size_t i = first + 1; i-- > 0;) {
        const double step = extended[i] * scale;
        const double best_vmin = std::floor(vmin / step) * step;
        const Edge edge(step, std::abs(offset));
        const double low = edge.le(vmin - best_vmin), high = edge.ge(vmax - best_vmin);
        ticks.clear();
        int in_view = 0;
        for (double k = low; k <= high; ++k) {
            double v = k * step + best_vmin;
            if (std::abs(v) < 1e-10 * step) v = 0;  // an exact zero, never -0 or 1e-17
            ticks.push_back(v + offset);
            in_view += (v >= vmin && v <= vmax) ? 1 : 0;
        }
        if (in_view >= 2) break;
    }
    return ticks;
}

// ScalarFormatter._set_format: the fewest decimals that tell the ticks apart
// to a thousandth of their range, the same for every label.
int decimals_for(const std::vector<double>& values) {
    if (values.empty()) return 0;
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    double range = *high - *low;
    if (range == 0) range = std::max(std::abs(*low), std::abs(*high));
    if (range == 0) range = 1;
    const int oom = int(std::floor(std::log10(range)));
    const double threshold = 1e-3 * std::pow(10.0, oom);
    int sigfigs = std::max(0, 3 - oom);
    while (sigfigs >= 0) {
        const double p = std::pow(10.0, sigfigs);
        double error = 0;
        for (double v : values) error = std::max(error, std::abs(v - std::round(v * p) / p));
        if (error >= threshold) break;
        --sigfigs;
    }
    return sigfigs + 1;
}


std::string superscript(int n) {
    static const char* const digits[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                         "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
    std::string s = n < 0 ? "\u207b" : "";
    for (char c : std::to_string(std::abs(n))) s += digits[c - '0'];
    return s;
}

// matplotlib's label for a minor tick on a log axis shorter than a decade: "2×10¹".
std::string coefficient_label(int coefficient, int exponent) {
    return std::to_string(coefficient) + "\u00d7" + power_of_ten_label(exponent);
}

}  // namespace

std::string format_fixed(double v, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    std::string s = text;
    if (s[0] != '-') return s;
    if (s.find_first_not_of("-0.") == std::string::npos) return s.substr(1);  // "-0.0" is zero
    return minus_sign + s.substr(1);
}

int tick_bins(float length, float font_size, bool horizontal) {
    if (!(font_size > 0)) return 9;
    const float per_tick = font_size * (horizontal ? 3.0f : 2.0f);
    return std::clamp(int(std::floor(length / per_tick)), 1, 9);
}

AxisTicks linear_ticks(double lo, double hi, int bins) {
    require_finite(lo, hi, "linear_ticks");
    if (lo > hi) std::swap(lo, hi);
    bins = std::max(1, bins);
    if (hi - lo <= 1e-12 * std::max(1.0, std::abs(lo))) {  // a single value: ticks around it
        const double delta = lo == 0 ? 1.0 : 0.05 * std::abs(lo);
        lo -= delta, hi += delta;
    }
    std::vector<double> shown;
    for (double v : raw_linear_ticks(lo, hi, bins))
        if (within(v, lo, hi)) shown.push_back(v);
    AxisTicks ticks;
    const int decimals = decimals_for(shown);
    for (double v : shown) ticks.major.push_back({v, format_fixed(v, decimals)});
    return ticks;
}

std::string power_of_ten_label(int exponent) { return "10" + superscript(exponent); }

AxisTicks log_ticks(double lo, double hi, int max_ticks) {
    require_finite(lo, hi, "log_ticks");
    if (!(lo > 0 && hi > 0)) throw std::invalid_argument("log_ticks: a log axis needs a positive range");
    if (lo > hi) std::swap(lo, hi);
    const double llo = std::log10(lo), lhi = std::log10(hi);
    const int first = int(std::floor(llo)), last = int(std::ceil(lhi));
    // LogLocator: every stride-th decade, so that about max_ticks fit.
    const int numticks = std::clamp(max_ticks, 2, 9);
    const int numdec = int(std::floor(lhi) - std::ceil(llo));
    int stride = (numdec + 1) / numticks + 1;
    if (stride >= numdec) stride = std::max(1, numdec - 1);
    auto floor_div = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
    AxisTicks ticks;
    for (int e = first; e <= last; ++e) {
        const double decade = std::pow(10.0, e);
        const bool major = e - stride * floor_div(e, stride) == 0;  // multiples of the stride, 10⁰ among them
        if (within(std::log10(decade), llo, lhi)) {
            if (major) ticks.major.push_back({decade, power_of_ten_label(e)});
            else if (numdec <= 10) ticks.minor.push_back({decade, ""});
        }
        if (stride != 1 || numdec > 10) continue;
        for (int c = 2; c <= 9; ++c)
            if (within(std::log10(c * decade), llo, lhi)) ticks.minor.push_back({c * decade, ""});
    }
    // Shorter than a decade: matplotlib labels the minor ticks too (only the
    // 3s when the axis spans more than 0.4 decades).
    if (lhi - llo <= 1.0 && ticks.major.size() < 2)
        for (Tick& t : ticks.minor) {
            const int e = int(std::floor(std::log10(t.value) + 1e-9));
            const int c = int(std::lround(t.value / std::pow(10.0, e)));
            if (lhi - llo <= 0.4 || c == 3) t.label = coefficient_label(c, e);
        }
    return ticks;
}

std::pair<double, double> linear_auto_range(double lo, double hi) {
    require_finite(lo, hi, "linear_auto_range");
    if (lo > hi) std::swap(lo, hi);
    if (hi - lo <= 1e-12 * std::max(1.0, std::abs(lo))) {  // nonsingular(expander=0.05)
        const double delta = lo == 0 ? 0.05 : 0.05 * std::abs(lo);
        return {lo - delta, hi + delta};
    }
    const double margin = 0.05 * (hi - lo);
    return {lo - margin, hi + margin};
}

std::pair<double, double> log_auto_range(double lo, double hi) {
    require_finite(lo, hi, "log_auto_range");
    if (!(lo > 0 && hi > 0)) throw std::invalid_argument("log_auto_range: a log axis needs positive data");
    const auto [a, b] = linear_auto_range(std::log10(lo), std::log10(hi));
    return {std::pow(10.0, a), std::pow(10.0, b)};
}

}  // namespace render
