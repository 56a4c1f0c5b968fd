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

WindowComparison compare_windows(std::span<const double> times, std::span<const double> w, const SaturationRule& rule) {
    if (times.size() != w.size()) throw std::invalid_argument("compare_windows: times and w differ in size");
    WindowComparison c;
    if (times.empty()) return c;
    // The slack keeps a sample exactly at a window's edge (T/r of a power of
    // ten) in the window it ends, whatever pow rounded.
    const double end = times.back() * (1 + 1e-12), middle = end / rule.window, start = middle / rule.window;
    std::size_t first_last = times.size(), first_previous = times.size();
    while (first_last > 0 && times[first_last - 1] > middle) --first_last;
    first_previous = first_last;
    while (first_previous > 0 && times[first_previous - 1] > start) --first_previous;
    c.previous_samples = first_last - first_previous;
    c.last_samples = times.size() - first_last;
    const auto minimum = static_cast<std::size_t>(rule.min_samples);
    if (c.previous_samples < minimum || c.last_samples < minimum) return c;
    c.compared = true;
    const MeanSem previous = mean_and_sem(w.subspan(first_previous, c.previous_samples));
    const MeanSem last = mean_and_sem(w.subspan(first_last, c.last_samples));
    c.previous_mean = previous.mean, c.previous_sem = previous.sem;
    c.last_mean = last.mean, c.last_sem = last.sem;
    const double difference = last.mean - previous.mean, error = std::hypot(previous.sem, last.sem);
    c.z = difference == 0 ? 0.0 : error > 0 ? difference / error : std::copysign(HUGE_VAL, difference);
    c.agree = std::abs(c.z) < rule.tolerance;
    return c;
}

SaturationDetector::SaturationDetector(const SaturationRule& rule) : rule_(rule) { rule_.validate(); }

bool SaturationDetector::add(double t, double w) {
    if (!times_.empty() && !(t > times_.back()))
        throw std::invalid_argument("SaturationDetector: times must increase");
    times_.push_back(t);
    w_.push_back(w);
    last_ = compare_windows(times_, w_, rule_);
    if (!last_.agree) {
        since_ = -1;
        return false;
    }
    if (since_ < 0) since_ = t;
    return t >= since_ * rule_.hold * (1 - 1e-12);  // the slack as in compare_windows
}

namespace {

// One run from an empty floor, W sampled at `counts` until the rule says
// saturated at or after min_time (in particles), else to the last count.
RoughnessRun run_until_saturated(int width, std::uint64_t seed, const std::vector<std::uint64_t>& counts,
                                 std::uint64_t min_count, const SaturationRule& rule) {
    Deposition run(DepositionParams{width, 0, false}, seed);
    SaturationDetector detector(rule);
    bool saturated = false;
    for (std::uint64_t n : counts) {
        run.drop(n - run.dropped());
        saturated = detector.add(static_cast<double>(n) / width, run.roughness()) && n >= min_count;
        if (saturated) break;
    }
    const WindowComparison& check = detector.last();
    // Without a comparison (a very short run) the last window is every sample.
    const double saturated_w = check.compared ? check.last_mean : mean_and_sem(detector.widths()).mean;
    return {seed, detector.times(), detector.widths(), saturated, detector.times().back(),
            saturated ? detector.agreeing_since() : -1.0, check, saturated_w};
}

}  // namespace

std::vector<RoughnessRun> roughness_until_saturated(int width, double min_time, double max_time, int points_per_decade,
                                                    int seeds, std::uint64_t seed, const SaturationRule& rule) {
    require_integer("width", width, 3, 10000000);
    require_number("max_time", max_time, 1.0, 1e9);
    require_number("min_time", min_time, 1.0, max_time);
    require_integer("points_per_decade", points_per_decade, 1, 1000);
    require_integer("seeds", seeds, 1, 1000000);
    rule.validate();
    const std::vector<std::uint64_t> counts = roughness_sample_counts(width, max_time, points_per_decade);
    const auto min_count = static_cast<std::uint64_t>(std::ceil(min_time * width));
    std::vector<RoughnessRun> runs;
    SplitMix64 run_seeds(seed);
    for (int r = 0; r < seeds; ++r) runs.push_back(run_until_saturated(width, run_seeds.next(), counts, min_count, rule));
    return runs;
}

RoughnessCurve mean_over_runs(int width, const std::vector<RoughnessRun>& runs) {
    if (runs.empty()) throw std::invalid_argument("mean_over_runs: no runs");
    std::size_t samples = runs[0].times.size();
    for (const auto& run : runs) samples = std::min(samples, run.times.size());
    RoughnessCurve curve{width, {}, {}, {}};
    std::vector<double> w(runs.size());
    for (std::size_t k = 0; k < samples; ++k) {
        for (std::size_t r = 0; r < runs.size(); ++r) w[r] = runs[r].w[k];
        const MeanSem m = mean_and_sem(w);
        curve.times.push_back(runs[0].times[k]);  // every run samples the same times
        curve.mean_w.push_back(m.mean);
        curve.sem_w.push_back(m.sem);
    }
    return curve;
}

}  // namespace sim
