#include "sim/deposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/check.hpp"

namespace sim {
namespace {

constexpr std::uint64_t most_recorded = std::numeric_limits<std::uint32_t>::max();

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
        double total = 0;
        for (double x : w[k]) total += x;
        const double mean = total / seeds;
        double squares = 0;
        for (double x : w[k]) squares += (x - mean) * (x - mean);
        curve.mean_w[k] = mean;
        curve.sem_w[k] = seeds > 1 ? std::sqrt(squares / (seeds - 1) / seeds) : 0.0;
    }
    return curve;
}

}  // namespace sim
