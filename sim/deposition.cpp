#include "sim/deposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/check.hpp"

namespace sim {
namespace {

constexpr std::uint64_t most_recorded = std::numeric_limits<std::uint32_t>::max();

struct MeanSem {
    double mean;
    double sem;  // sample deviation / sqrt(n); 0 for one value
};

// Two passes, in the values' order: the same values give the same bits.
MeanSem mean_and_sem(std::span<const double> values) {
    const auto n = static_cast<double>(values.size());
    double total = 0;
    for (double x : values) total += x;
    const double mean = total / n;
    double squares = 0;
    for (double x : values) squares += (x - mean) * (x - mean);
    return {mean, values.size() > 1 ? std::sqrt(squares / (n - 1) / n) : 0.0};
}

}  // namespace

void DepositionParams::validate() const {
    require_integer("width", width, 3, 10000000);  // 3 keeps a column's two neighbours distinct
    if (particles > most_recorded)
        throw ParameterError("particles", std::to_string(particles),
                             "an integer from 0 to " + std::to_string(most_recorded));
}

Deposition::Deposition(const DepositionParams& params, std::uint64_t seed) : params_(params), rng_(seed) {
    params_.validate();
    heights_.assign(static_cast<std::size_t>(params_.width), 0);
    if (!params_.record) return;
    columns_.resize(heights_.size());
    // A column's count is about Poisson(n): n + 4 sqrt(n) covers nearly every
    // column, so few ever reallocate and the slack stays near 4 / sqrt(n).
    const double n = static_cast<double>(params_.particles) / params_.width;
    const auto room = static_cast<std::size_t>(n + 4 * std::sqrt(n) + 8);
    for (auto& column : columns_) column.reserve(room);
}

void Deposition::drop() {
    const std::size_t n = heights_.size();
    const std::size_t i = rng_.below(n);
    const std::size_t left = i == 0 ? n - 1 : i - 1, right = i + 1 == n ? 0 : i + 1;
    const std::int64_t h = std::max({heights_[left], heights_[i] + 1, heights_[right]});
    if (params_.record) {
        if (dropped_ == most_recorded)
            throw std::length_error("ballistic deposition: the deposit store holds at most 4294967295 particles");
        // h <= dropped_ + 1 <= most_recorded: a column grows by at most one particle's worth per drop.
        columns_[i].push_back({static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(dropped_)});
    }
    heights_[i] = h;
    ++dropped_;
}

void Deposition::drop(std::uint64_t n) {
    for (std::uint64_t k = 0; k < n; ++k) drop();
}

double Deposition::mean_height() const {
    std::int64_t total = 0;  // exact, unlike a sum of doubles: each height is at most dropped()
    for (std::int64_t h : heights_) total += h;
    return static_cast<double>(total) / static_cast<double>(heights_.size());
}

double Deposition::roughness() const {
    // Two passes: heights grow large while W stays small, and sum(h^2)/L - mean^2 would cancel away W.
    const double mean = mean_height();
    double squares = 0;
    for (std::int64_t h : heights_) {
        const double dev = static_cast<double>(h) - mean;
        squares += dev * dev;
    }
    return std::sqrt(squares / static_cast<double>(heights_.size()));
}

std::vector<Deposition::Particle> Deposition::particles() const {
    if (!params_.record)
        throw std::logic_error("ballistic deposition: particles() needs record = true");
    std::vector<Particle> out(dropped_);
    for (std::size_t c = 0; c < columns_.size(); ++c)
        for (const Cell& cell : columns_[c])
            out[cell.arrival] = {static_cast<std::int32_t>(c), cell.height, cell.arrival};
    return out;
}

std::uint64_t Deposition::cells() const {
    std::uint64_t total = 0;
    for (const auto& column : columns_) total += column.size();
    return total;
}

std::size_t Deposition::memory_bytes() const {
    std::size_t bytes = heights_.capacity() * sizeof(std::int64_t) + columns_.capacity() * sizeof(columns_[0]);
    for (const auto& column : columns_) bytes += column.capacity() * sizeof(Cell);
    return bytes;
}

std::vector<std::uint64_t> roughness_sample_counts(int width, double max_time, int points_per_decade) {
    // 10^(k/ppd) monolayers, rounded; the slack keeps max_time itself when it
    // is a power of ten that pow rounds up.
    std::vector<std::uint64_t> counts;
    for (int k = 0;; ++k) {
        const double t = std::pow(10.0, static_cast<double>(k) / points_per_decade);
        if (t > max_time * (1 + 1e-12)) break;
        const auto n = static_cast<std::uint64_t>(std::llround(t * width));
        if (counts.empty() || n > counts.back()) counts.push_back(n);
    }
    return counts;
}

RoughnessCurve roughness_curve(int width, double max_time, int points_per_decade, int seeds, std::uint64_t seed) {
    require_integer("width", width, 3, 10000000);
    require_number("max_time", max_time, 1.0, 1e9);
    require_integer("points_per_decade", points_per_decade, 1, 1000);
    require_integer("seeds", seeds, 1, 1000000);

    const std::vector<std::uint64_t> counts = roughness_sample_counts(width, max_time, points_per_decade);
    RoughnessCurve curve{width, {}, std::vector<double>(counts.size(), 0.0), std::vector<double>(counts.size(), 0.0)};
    for (std::uint64_t n : counts) curve.times.push_back(static_cast<double>(n) / width);

    // w[k][r]: W at time k in run r; averaged afterwards in run order, two passes.
    std::vector<std::vector<double>> w(counts.size(), std::vector<double>(static_cast<std::size_t>(seeds)));
    SplitMix64 run_seeds(seed);
    for (int r = 0; r < seeds; ++r) {
        Deposition run(DepositionParams{width, 0, false}, run_seeds.next());
        for (std::size_t k = 0; k < counts.size(); ++k) {
            run.drop(counts[k] - run.dropped());
            w[k][static_cast<std::size_t>(r)] = run.roughness();
        }
    }
    for (std::size_t k = 0; k < counts.size(); ++k) {
        const MeanSem m = mean_and_sem(w[k]);
        curve.mean_w[k] = m.mean;
        curve.sem_w[k] = m.sem;
    }
    return curve;
}

void SaturationRule::validate() const {
    require_number("window", window, 1.1, 100);
    require_number("tolerance", tolerance, 0.01, 100);
    require_number("hold", hold, 1, 100);
    require_integer("min_samples", min_samples, 2, 1000);
}

namespace {

// The indices [first, times.size()) of the samples in (end / r, end], where
// end = times.back(), and [first_previous, first) of those in the window before.
struct Windows {
    std::size_t first_previous, first;
};

Windows windows_ending_last(std::span<const double> times, double r) {
    // The slack keeps a sample exactly at a window's edge (T/r of a power of
    // ten) in the window it ends, whatever pow rounded.
    const double end = times.back() * (1 + 1e-12), middle = end / r, start = middle / r;
    std::size_t first = times.size();
    while (first > 0 && times[first - 1] > middle) --first;
    std::size_t first_previous = first;
    while (first_previous > 0 && times[first_previous - 1] > start) --first_previous;
    return {first_previous, first};
}

double mean_of(std::span<const double> values) { return mean_and_sem(values).mean; }

}  // namespace

WindowComparison compare_windows(std::span<const double> times, std::span<const std::vector<double>> w,
                                 const SaturationRule& rule) {
    if (w.empty()) throw std::invalid_argument("compare_windows: no runs");
    for (const auto& run : w)
        if (run.size() != times.size()) throw std::invalid_argument("compare_windows: a run's w and times differ in size");
    WindowComparison c;
    if (times.empty()) return c;
    const Windows at = windows_ending_last(times, rule.window);
    c.previous_samples = at.first - at.first_previous;
    c.last_samples = times.size() - at.first;
    const auto minimum = static_cast<std::size_t>(rule.min_samples);
    if (c.previous_samples < minimum || c.last_samples < minimum) return c;
    c.compared = true;
    // Per run its two window means, then the ensemble's statistics across runs, in run order.
    std::vector<double> previous, last, difference;
    for (const auto& run : w) {
        const std::span<const double> all(run);
        previous.push_back(mean_of(all.subspan(at.first_previous, c.previous_samples)));
        last.push_back(mean_of(all.subspan(at.first, c.last_samples)));
        difference.push_back(last.back() - previous.back());
    }
    const MeanSem p = mean_and_sem(previous), l = mean_and_sem(last), d = mean_and_sem(difference);
    c.previous_mean = p.mean, c.previous_sem = p.sem;
    c.last_mean = l.mean, c.last_sem = l.sem;
    c.difference = d.mean, c.difference_sem = d.sem;
    c.z = d.mean == 0 ? 0.0 : d.sem > 0 ? d.mean / d.sem : std::copysign(HUGE_VAL, d.mean);
    c.agree = std::abs(c.z) < rule.tolerance;
    return c;
}

SaturationDetector::SaturationDetector(const SaturationRule& rule, int runs) : rule_(rule) {
    rule_.validate();
    require_integer("runs", runs, 1, 1000000);
    w_.resize(static_cast<std::size_t>(runs));
}

bool SaturationDetector::add(double t, std::span<const double> w) {
    if (!times_.empty() && !(t > times_.back()))
        throw std::invalid_argument("SaturationDetector: times must increase");
    if (w.size() != w_.size()) throw std::invalid_argument("SaturationDetector: one W per run");
    times_.push_back(t);
    for (std::size_t r = 0; r < w.size(); ++r) w_[r].push_back(w[r]);
    last_ = compare_windows(times_, w_, rule_);
    if (!last_.agree) {
        since_ = -1;
        return false;
    }
    if (since_ < 0) since_ = t;
    return t >= since_ * rule_.hold * (1 - 1e-12);  // the slack as in compare_windows
}

namespace {

// W_sat: the ensemble's last window at the stop; without a comparison (a
// very short run) the last window is every sample.
void set_saturated_w(RoughnessEnsemble& e) {
    if (e.check.compared) {
        e.saturated_w = e.check.last_mean, e.saturated_w_sem = e.check.last_sem;
        return;
    }
    std::vector<double> per_run;
    for (const auto& run : e.w) per_run.push_back(mean_and_sem(run).mean);
    const MeanSem m = mean_and_sem(per_run);
    e.saturated_w = m.mean, e.saturated_w_sem = m.sem;
}

}  // namespace

RoughnessEnsemble roughness_until_saturated(int width, double min_time, double max_time, int points_per_decade,
                                            int seeds, std::uint64_t seed, const SaturationRule& rule) {
    require_integer("width", width, 3, 10000000);
    require_number("max_time", max_time, 1.0, 1e9);
    require_number("min_time", min_time, 1.0, max_time);
    require_integer("points_per_decade", points_per_decade, 1, 1000);
    require_integer("seeds", seeds, 1, 1000000);
    SaturationDetector detector(rule, seeds);
    const std::vector<std::uint64_t> counts = roughness_sample_counts(width, max_time, points_per_decade);
    const auto min_count = static_cast<std::uint64_t>(std::ceil(min_time * width));
    RoughnessEnsemble e{width, {}, {}, {}, false, 0, -1, {}, 0, 0};
    std::vector<Deposition> runs;
    SplitMix64 run_seeds(seed);
    for (int r = 0; r < seeds; ++r) {
        e.seeds.push_back(run_seeds.next());
        runs.emplace_back(DepositionParams{width, 0, false}, e.seeds.back());
    }
    // Each run owns its generator, so advancing them in turn leaves every
    // run's draws as they would be alone; the order is fixed, so is the result.
    std::vector<double> w(runs.size());
    for (std::uint64_t n : counts) {
        for (std::size_t r = 0; r < runs.size(); ++r) {
            runs[r].drop(n - runs[r].dropped());
            w[r] = runs[r].roughness();
        }
        e.saturated = detector.add(static_cast<double>(n) / width, w) && n >= min_count;
        if (e.saturated) break;
    }
    e.times = detector.times();
    e.w = detector.widths();
    e.stop_time = e.times.back();
    e.agreeing_since = e.saturated ? detector.agreeing_since() : -1.0;
    e.check = detector.last();
    set_saturated_w(e);
    return e;
}

RoughnessCurve mean_over_runs(const RoughnessEnsemble& ensemble) {
    RoughnessCurve curve{ensemble.width, ensemble.times, {}, {}};
    std::vector<double> w(ensemble.w.size());
    for (std::size_t k = 0; k < ensemble.times.size(); ++k) {
        for (std::size_t r = 0; r < w.size(); ++r) w[r] = ensemble.w[r][k];
        const MeanSem m = mean_and_sem(w);
        curve.mean_w.push_back(m.mean);
        curve.sem_w.push_back(m.sem);
    }
    return curve;
}

}  // namespace sim
