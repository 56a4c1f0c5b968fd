#include "sim/percolation_threshold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "sim/check.hpp"

namespace sim {
namespace {

constexpr int max_size = 4096;  // N = 2^24 sites: 16 bytes each, and n fits in 32 bits
constexpr int max_samples = 100'000'000;

void validate(int size, int samples) {
    require_integer("size", size, 1, max_size);
    require_integer("samples", samples, 1, max_samples);
}

// Union-find over the sites of an L x L torus with union by size and path
// compression; dx, dy hold each site's displacement to its parent in
// unwrapped lattice units, so a find also gives the displacement to the root.
// The four fields of a site sit together: a find touches one cache line per
// site instead of four (about a quarter faster at L = 128 and 256 in the bench).
class WrapTracker {
public:
    explicit WrapTracker(int size) : size_(size) {
        const std::size_t n = static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
        sites_.assign(n, Site{});
    }

    void reset() {
        std::fill(sites_.begin(), sites_.end(), Site{});
        points_ = {};
        occupied_ = 0;
    }

    bool occupied(std::uint32_t site) const { return sites_[site].parent != empty; }
    bool wrapped_both_ways() const { return points_.horizontal != 0 && points_.vertical != 0; }
    const WrappingPoints& points() const { return points_; }

    // Occupies an empty site and joins it to its occupied neighbours.
    void occupy(std::uint32_t site) {
        ++occupied_;
        sites_[site] = {static_cast<std::int32_t>(site), 1, 0, 0};
        const std::uint32_t l = static_cast<std::uint32_t>(size_);
        const std::uint32_t x = site % l, row = site - x;
        // Neighbours across the edge are the other side of the torus, but one
        // step away in unwrapped units: that is what makes a loop round the
        // torus add up to a multiple of L.
        join(site, x + 1 == l ? row : site + 1, 1, 0);
        join(site, x == 0 ? row + l - 1 : site - 1, -1, 0);
        const std::uint32_t n = l * l;
        join(site, site + l >= n ? site + l - n : site + l, 0, 1);
        join(site, site < l ? site + n - l : site - l, 0, -1);
    }

private:
    static constexpr std::int32_t empty = -1;

    struct Site {
        std::int32_t parent = empty;     // empty, or the parent (itself at a root)
        std::int32_t cluster_size = 0;   // meaningful at roots only
        std::int32_t dx = 0, dy = 0;     // displacement to the parent
    };

    struct Root {
        std::int32_t root, dx, dy;  // the root and the displacement from the site to it
    };

    Root find(std::int32_t site) {
        std::int32_t root = site, dx = 0, dy = 0;
        while (sites_[root].parent != root) {
            dx += sites_[root].dx;
            dy += sites_[root].dy;
            root = sites_[root].parent;
        }
        // Path compression: every site on the path now points at the root,
        // with its own displacement to it (the total minus what lies behind it).
        std::int32_t s = site, rx = dx, ry = dy;
        while (s != root) {
            Site& at = sites_[s];
            const std::int32_t next = at.parent, ox = at.dx, oy = at.dy;
            at.parent = root;
            at.dx = rx;
            at.dy = ry;
            rx -= ox;
            ry -= oy;
            s = next;
        }
        return {root, dx, dy};
    }

    // The bond from site to its neighbour, which lies (ex, ey) away.
    void join(std::uint32_t site, std::uint32_t neighbour, std::int32_t ex, std::int32_t ey) {
        if (sites_[neighbour].parent == empty) return;
        const Root a = find(static_cast<std::int32_t>(site));
        const Root b = find(static_cast<std::int32_t>(neighbour));
        // The root seen from the site directly, and via the neighbour.
        const std::int32_t wx = a.dx - (ex + b.dx), wy = a.dy - (ey + b.dy);
        if (a.root == b.root) {
            // A loop: it winds round the torus wherever the two routes disagree.
            if (wx != 0 && points_.horizontal == 0) points_.horizontal = occupied_;
            if (wy != 0 && points_.vertical == 0) points_.vertical = occupied_;
            return;
        }
        // Union by size; the hanging root's displacement to the new root is
        // the route from it to its own site, across the bond, and on up.
        Site &ra = sites_[a.root], &rb = sites_[b.root];
        if (ra.cluster_size < rb.cluster_size) {
            ra = {b.root, ra.cluster_size, -wx, -wy};
            rb.cluster_size += ra.cluster_size;
        } else {
            rb = {a.root, rb.cluster_size, wx, wy};
            ra.cluster_size += rb.cluster_size;
        }
    }

    int size_;
    std::vector<Site> sites_;
    WrappingPoints points_;
    std::uint32_t occupied_ = 0;
};

// The event time of one sample for the criterion; 0 = never. For
// one_direction the sample has two (horizontal and vertical), handled apart.
std::uint32_t event(const WrappingPoints& w, WrapCriterion criterion) {
    if (criterion == WrapCriterion::either_direction) {
        if (w.horizontal == 0 || w.vertical == 0) return std::max(w.horizontal, w.vertical);
        return std::min(w.horizontal, w.vertical);
    }
    if (w.horizontal == 0 || w.vertical == 0) return 0;
    return std::max(w.horizontal, w.vertical);
}

// The binomial convolution over one lattice of N sites. Weights come from
// logarithms (log C(N,n) + n log p + (N-n) log(1-p), then exp): C(N,n) and
// p^n overflow and underflow long before N = 65536. Only the n within 20
// standard deviations of Np are summed: the rest weigh less than e^-200.
class Convolution {
public:
    Convolution(const std::vector<WrappingPoints>& points, int size, WrapCriterion criterion)
        : n_(static_cast<std::uint32_t>(size) * static_cast<std::uint32_t>(size)),
          criterion_(criterion),
          cumulative_(n_ + 1, 0.0),
          log_factorial_(n_ + 1, 0.0) {
        // cumulative_[n] = R_L(n), the fraction of events by occupation n.
        const double share = criterion == WrapCriterion::one_direction ? 0.5 : 1.0;
        const double weight = share / static_cast<double>(points.size());
        for (const WrappingPoints& w : points) {
            if (criterion == WrapCriterion::one_direction) {
                if (w.horizontal != 0) cumulative_[w.horizontal] += weight;
                if (w.vertical != 0) cumulative_[w.vertical] += weight;
            } else if (const std::uint32_t t = event(w, criterion); t != 0) {
                cumulative_[t] += weight;
            }
        }
        for (std::uint32_t n = 1; n <= n_; ++n) cumulative_[n] += cumulative_[n - 1];
        for (std::uint32_t n = 0; n <= n_; ++n) log_factorial_[n] = std::lgamma(static_cast<double>(n) + 1.0);
    }

    double at(double p) const {
        if (p <= 0) return cumulative_[0];
        if (p >= 1) return cumulative_[n_];
        const Window w = window(p);
        double sum = 0;
        for (std::uint32_t n = w.low; n <= w.high; ++n) sum += std::exp(log_binomial(n_, n, p)) * cumulative_[n];
        return sum;
    }

    // Sample spread of R_L(p): each sample's contribution is the probability
    // that Bin(N, p) reaches its event time, tail(t) = P(Bin >= t); its slope
    // in p is N * P(Bin(N-1, p) = t - 1).
    struct Spread {
        double mean, standard_error, slope;
    };
    Spread spread(const std::vector<WrappingPoints>& points, double p) const {
        const Window w = window(p);
        std::vector<double> tail(static_cast<std::size_t>(w.high - w.low) + 2, 0.0);
        for (std::uint32_t n = w.high + 1; n-- > w.low;)
            tail[n - w.low] = tail[n - w.low + 1] + std::exp(log_binomial(n_, n, p));
        auto tail_at = [&](std::uint32_t t) {
            if (t == 0) return 0.0;  // never happened
            if (t < w.low) return 1.0;
            if (t > w.high) return 0.0;
            return tail[t - w.low];
        };
        auto slope_at = [&](std::uint32_t t) {
            if (t == 0) return 0.0;
            return static_cast<double>(n_) * std::exp(log_binomial(n_ - 1, t - 1, p));
        };
        double sum = 0, sum_sq = 0, slope = 0;
        for (const WrappingPoints& pt : points) {
            double x, dx;
            if (criterion_ == WrapCriterion::one_direction) {
                x = 0.5 * (tail_at(pt.horizontal) + tail_at(pt.vertical));
                dx = 0.5 * (slope_at(pt.horizontal) + slope_at(pt.vertical));
            } else {
                const std::uint32_t t = event(pt, criterion_);
                x = tail_at(t);
                dx = slope_at(t);
            }
            sum += x;
            sum_sq += x * x;
            slope += dx;
        }
        const double s = static_cast<double>(points.size());
        const double mean = sum / s;
        const double variance = points.size() > 1 ? std::max(0.0, (sum_sq - s * mean * mean) / (s - 1)) : 0.0;
        return {mean, points.size() > 1 ? std::sqrt(variance / s) : std::numeric_limits<double>::quiet_NaN(),
                slope / s};
    }

private:
    struct Window {
        std::uint32_t low, high;
    };
    Window window(double p) const {
        const double mean = p * n_, half = 20.0 * std::sqrt(mean * (1 - p)) + 20.0;
        const double low = std::max(0.0, std::floor(mean - half)), high = std::min<double>(n_, std::ceil(mean + half));
        return {static_cast<std::uint32_t>(low), static_cast<std::uint32_t>(high)};
    }

    double log_binomial(std::uint32_t total, std::uint32_t n, double p) const {
        return log_factorial_[total] - log_factorial_[n] - log_factorial_[total - n] +
               static_cast<double>(n) * std::log(p) + static_cast<double>(total - n) * std::log1p(-p);
    }

    std::uint32_t n_;
    WrapCriterion criterion_;
    std::vector<double> cumulative_;
    std::vector<double> log_factorial_;
};

}  // namespace

double wrapping_probability_at_threshold(WrapCriterion criterion) {
    switch (criterion) {
        case WrapCriterion::one_direction: return 0.521058290;
        case WrapCriterion::either_direction: return 0.690473725;
        case WrapCriterion::both_directions: return 0.351642855;
    }
    throw std::invalid_argument("wrap criterion is not one_direction, either_direction or both_directions");
}

WrappingPoints wrapping_points_for_order(int size, std::span<const std::uint32_t> order) {
    require_integer("size", size, 1, max_size);
    const std::uint32_t n = static_cast<std::uint32_t>(size) * static_cast<std::uint32_t>(size);
    WrapTracker tracker(size);
    for (const std::uint32_t site : order) {
        if (site >= n)
            throw std::invalid_argument("site = " + std::to_string(site) + " is not allowed: sites must be below " +
                                        std::to_string(n));
        if (tracker.occupied(site))
            throw std::invalid_argument("site = " + std::to_string(site) + " is not allowed: it is already occupied");
        tracker.occupy(site);
    }
    return tracker.points();
}

std::vector<WrappingPoints> wrapping_points(int size, int samples, Random& rng) {
    validate(size, samples);
    const std::uint32_t n = static_cast<std::uint32_t>(size) * static_cast<std::uint32_t>(size);
    WrapTracker tracker(size);
    std::vector<std::uint32_t> order(n);
    std::vector<WrappingPoints> result;
    result.reserve(static_cast<std::size_t>(samples));
    for (int s = 0; s < samples; ++s) {
        tracker.reset();
        std::iota(order.begin(), order.end(), 0u);
        // Fisher-Yates one step at a time: the i-th site is uniform among the
        // sites still empty, so the sample can stop at the wrapping point
        // (about 0.6 N) and skip the draws for the rest of the permutation.
        for (std::uint32_t i = 0; i < n && !tracker.wrapped_both_ways(); ++i) {
            const std::uint32_t j = i + static_cast<std::uint32_t>(rng.below(n - i));
            std::swap(order[i], order[j]);
            tracker.occupy(order[i]);
        }
        result.push_back(tracker.points());
    }
    return result;
}

std::vector<std::uint32_t> wrapping_occupation(int size, int samples, Random& rng) {
    const std::vector<WrappingPoints> points = wrapping_points(size, samples, rng);
    std::vector<std::uint32_t> first;
    first.reserve(points.size());
    for (const WrappingPoints& w : points) first.push_back(event(w, WrapCriterion::either_direction));
    return first;
}

double wrapping_probability(const std::vector<WrappingPoints>& points, int size, WrapCriterion criterion,
                            double p) {
    require_integer("size", size, 1, max_size);
    require_number("p", p, 0.0, 1.0);
    if (points.empty()) throw std::invalid_argument("points is empty: at least one sample is needed");
    return Convolution(points, size, criterion).at(p);
}

std::vector<double> wrapping_probability(const std::vector<WrappingPoints>& points, int size, WrapCriterion criterion,
                                         std::span<const double> ps) {
    require_integer("size", size, 1, max_size);
    for (const double p : ps) require_number("p", p, 0.0, 1.0);
    if (points.empty()) throw std::invalid_argument("points is empty: at least one sample is needed");
    const Convolution r(points, size, criterion);
    std::vector<double> values;
    values.reserve(ps.size());
    for (const double p : ps) values.push_back(r.at(p));
    return values;
}

std::optional<double> wrapping_crossing(const std::vector<WrappingPoints>& a, int size_a,
                                        const std::vector<WrappingPoints>& b, int size_b, WrapCriterion criterion,
                                        double low, double high, int steps) {
    require_integer("size_a", size_a, 1, max_size);
    require_integer("size_b", size_b, 1, max_size);
    require_number("low", low, 0.0, 1.0);
    require_number("high", high, low, 1.0);
    require_integer("steps", steps, 1, 1'000'000);
    if (a.empty() || b.empty()) throw std::invalid_argument("points is empty: at least one sample is needed");
    const Convolution ra(a, size_a, criterion), rb(b, size_b, criterion);
    auto difference = [&](double p) { return rb.at(p) - ra.at(p); };
    std::vector<double> p(static_cast<std::size_t>(steps) + 1), d(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
        p[i] = low + (high - low) * static_cast<double>(i) / steps;
        d[i] = difference(p[i]);
    }
    const std::ptrdiff_t lowest = std::min_element(d.begin(), d.end()) - d.begin();
    const std::ptrdiff_t highest = std::max_element(d.begin(), d.end()) - d.begin();
    if (!(d[lowest] < 0 && d[highest] > 0)) return std::nullopt;
    // From the most negative towards the most positive, either way along p.
    const std::ptrdiff_t step = lowest < highest ? 1 : -1;
    std::ptrdiff_t i = lowest;
    while (d[i + step] < 0) i += step;
    double below = p[i], above = p[i + step];  // difference < 0 at `below`, >= 0 at `above`
    while (std::abs(above - below) > 1e-12) {
        const double mid = 0.5 * (below + above);
        (difference(mid) < 0 ? below : above) = mid;
    }
    return 0.5 * (below + above);
}

ThresholdExtrapolation extrapolate_threshold(std::span<const ThresholdEstimate> estimates) {
    if (estimates.size() < 2)
        throw std::invalid_argument("estimates = " + std::to_string(estimates.size()) +
                                    " is not allowed: two lattice sizes at least, to fit a line");
    double s = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const ThresholdEstimate& e : estimates) {
        if (!(std::isfinite(e.standard_error) && e.standard_error > 0))
            throw std::invalid_argument("standard_error = " + shown(e.standard_error) +
                                        " is not allowed: a finite number above 0 (at L = " + std::to_string(e.size) +
                                        ")");
        for (const ThresholdEstimate& other : estimates)
            if (&other != &e && other.size == e.size)
                throw std::invalid_argument("size = " + std::to_string(e.size) +
                                            " is not allowed: each lattice size once");
        const double x = std::pow(static_cast<double>(e.size), -threshold_correction_exponent);
        const double w = 1.0 / (e.standard_error * e.standard_error);
        s += w;
        sx += w * x;
        sy += w * e.p_c;
        sxx += w * x * x;
        sxy += w * x * e.p_c;
    }
    // The normal equations of y = a + b x; their inverse gives the variances.
    const double det = s * sxx - sx * sx;
    ThresholdExtrapolation fit{};
    fit.p_c = (sxx * sy - sx * sxy) / det;
    fit.slope = (s * sxy - sx * sy) / det;
    fit.standard_error = std::sqrt(sxx / det);
    fit.slope_error = std::sqrt(s / det);
    for (const ThresholdEstimate& e : estimates) {
        const double x = std::pow(static_cast<double>(e.size), -threshold_correction_exponent);
        const double residual = (e.p_c - fit.p_c - fit.slope * x) / e.standard_error;
        fit.chi_squared += residual * residual;
    }
    fit.degrees_of_freedom = static_cast<int>(estimates.size()) - 2;
    return fit;
}

ThresholdEstimate threshold_from_wrapping(const std::vector<WrappingPoints>& points, int size,
                                          WrapCriterion criterion) {
    require_integer("size", size, 1, max_size);
    if (points.empty()) throw std::invalid_argument("points is empty: at least one sample is needed");
    require_integer("samples", static_cast<long long>(points.size()), 1, max_samples);
    const double target = wrapping_probability_at_threshold(criterion);
    const Convolution r(points, size, criterion);
    if (r.at(1.0) < target)
        throw std::invalid_argument("points never reach the wrapping probability at p_c: too few samples wrap");
    // R_L(p) rises from 0 to 1: bisect until the bracket stops shrinking.
    double low = 0, high = 1;
    for (int i = 0; i < 200 && high - low > 1e-15; ++i) {
        const double mid = 0.5 * (low + high);
        (r.at(mid) < target ? low : high) = mid;
    }
    const double p_c = 0.5 * (low + high);
    const auto spread = r.spread(points, p_c);
    // Delta method: the spread of R_L at p_c over its slope there.
    return {p_c, spread.standard_error / spread.slope, static_cast<int>(points.size()), size};
}

ThresholdEstimate newman_ziff_threshold(int size, int samples, Random& rng, WrapCriterion criterion) {
    validate(size, samples);
    return threshold_from_wrapping(wrapping_points(size, samples, rng), size, criterion);
}

}  // namespace sim
