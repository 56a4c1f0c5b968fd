#pragma once
// Ballistic deposition (Vold 1959; Family & Vicsek 1985): particles fall
// straight down into random columns of a periodic strip and stick at the
// first cell that touches the deposit, below or to either side. The surface
// roughens as in the KPZ class: W ~ t^beta early (beta = 1/3), saturating at
// W ~ L^alpha (alpha = 1/2) after a time ~ L^(3/2).
//
// A particle dropped into column i sticks at
//     h[i] = max(h[i-1], h[i] + 1, h[i+1])        (neighbours wrap)
// which is exactly where the fall would stop: on top of its own column, or
// level with a taller neighbour's top particle that it touches on the way
// down. So drop() is O(1) from the heights; no cell is ever scanned.
//
// Randomness: one rng.below(width) per particle, nothing else.

#include <cstdint>
#include <span>
#include <vector>

#include "sim/random.hpp"

namespace sim {

struct DepositionParams {
    int width = 500;  // columns L, periodic, 3..10,000,000
    std::uint64_t particles =
        250000;          // particles the deposit makes room for up front (drop() may go past), 0..4,294,967,295
    bool record = true;  // keep every particle's cell; off when only the heights matter (roughness runs)

    void validate() const;  // throws std::invalid_argument naming the bad parameter
};

class Deposition {
public:
    // A particle as particles() lists it.
    struct Particle {
        std::int32_t column;    // 0..width-1
        std::int64_t height;    // 1 = resting on the floor
        std::uint64_t arrival;  // 0 for the first particle dropped, then 1, 2, ...
    };

    // Owns its generator, seeded with `seed`; starts with an empty floor.
    Deposition(const DepositionParams& params, std::uint64_t seed);

    void drop();                 // one particle; std::length_error past 4,294,967,295 recorded particles
    void drop(std::uint64_t n);  // n particles

    std::uint64_t dropped() const { return dropped_; }
    // Per column, the height of its top particle (0 = bare floor).
    const std::vector<std::int64_t>& heights() const { return heights_; }
    double mean_height() const;
    double roughness() const;  // W: standard deviation of the heights, population (divides by L)

    // Every particle, in arrival order (so the first k are the deposit after
    // k drops, as an animation wants). Throws std::logic_error when record is off.
    std::vector<Particle> particles() const;
    // Occupied cells in the deposit store: dropped() when recording, else 0.
    std::uint64_t cells() const;
    // Bytes held by the heights and the deposit store (capacity, not size).
    std::size_t memory_bytes() const;
    const DepositionParams& params() const { return params_; }

private:
    // One particle's cell: its column is the store it sits in. 32 bits each
    // keep the deposit at 8 bytes a particle; record caps the count to fit.
    struct Cell {
        std::uint32_t height;
        std::uint32_t arrival;
    };

    DepositionParams params_;
    Random rng_;
    std::vector<std::int64_t> heights_;
    std::vector<std::vector<Cell>> columns_;  // per column, its particles bottom to top (heights rise, with holes)
    std::uint64_t dropped_ = 0;
};

// W(L, t) at logarithmically spaced times, averaged over independent runs.
struct RoughnessCurve {
    int width;                   // L
    std::vector<double> times;   // t in monolayers (L particles), 10^(k / points_per_decade) rounded to whole particles
    std::vector<double> mean_w;  // W at each time, mean over the runs
    std::vector<double> sem_w;   // standard error of that mean (sample deviation / sqrt(runs)); 0 for one run
};

// Runs `seeds` depositions of width L (3..10,000,000) from t = 1 up to
// max_time monolayers (1..1e9), recording only the heights, and samples W at
// times 10^(k / points_per_decade) (1..1000 a decade), k = 0, 1, ...; each
// time is rounded to a whole number of particles, repeats dropped. Run r is
// seeded with the r-th output of SplitMix64(seed). seeds: 1..1,000,000.
RoughnessCurve roughness_curve(int width, double max_time, int points_per_decade, int seeds, std::uint64_t seed);
// The times roughness_curve samples, in particles (times t are counts / L).
std::vector<std::uint64_t> roughness_sample_counts(int width, double max_time, int points_per_decade);

// When W(t) has stopped growing, judged on an ensemble of independent runs
// sampled together at log-spaced times T. Two windows end at T: the last,
// times in (T/r, T], and the one before, (T/r^2, T/r]. While W grows as
// t^beta the last window's mean exceeds the other's by r^beta (39% for
// r = 3, beta = 0.3); saturated, they differ by noise. One run's W wanders
// over about the saturation time, so its own samples are correlated and
// their spread is no standard error; the runs are independent, so the spread
// of per-run window means across runs is one. Even so a single agreement can
// be luck during growth: the windows must agree at every sample over a
// further factor `hold` in time.
struct SaturationRule {
    double window = 3;  // r, the windows' ratio of end to start time: 1.1..100
    double tolerance = 2;  // windows agree when their means differ by less than this many standard errors: 0.01..100
    double hold = 2;       // they must have agreed at every sample since T/hold: 1..100 (1: a single agreement)
    int min_samples = 3;   // samples each window needs before the two are compared: 2..1000

    void validate() const;  // throws std::invalid_argument naming the bad field
};

// One comparison of the two windows ending at the last sample, on an
// ensemble: each run's mean W over each window, then over the runs.
struct WindowComparison {
    bool compared = false;  // both windows held min_samples samples
    std::size_t previous_samples = 0, last_samples = 0;  // sample times in each window
    double previous_mean = 0, previous_sem = 0;  // W over (T/r^2, T/r]: mean over runs, standard error across runs
    double last_mean = 0, last_sem = 0;          // W over (T/r, T]
    // last - previous, and its standard error from the spread of the runs'
    // own differences: a run's two windows are correlated, so the paired
    // error is the right one (0 for one run).
    double difference = 0, difference_sem = 0;
    double z = 0;        // difference / difference_sem; 0 for no difference, +-inf for one without spread
    bool agree = false;  // compared and |z| < tolerance
};

// Compares the windows ending at times.back(); times increasing, w[r] run r's
// W at each time (every run the same size as times, one run at least).
WindowComparison compare_windows(std::span<const double> times, std::span<const std::vector<double>> w,
                                 const SaturationRule& rule);

// Feeds an ensemble's samples in time order and says when its W has saturated.
class SaturationDetector {
public:
    SaturationDetector(const SaturationRule& rule, int runs);  // validates the rule; runs >= 1
    // Adds each run's W at time t (> the previous t; one value per run); true
    // once the windows have agreed at every sample from some t0 <= t / hold up to t.
    bool add(double t, std::span<const double> w);
    const WindowComparison& last() const { return last_; }  // the comparison made at the latest sample
    double agreeing_since() const { return since_; }        // the first time of the current agreement, or -1
    const std::vector<double>& times() const { return times_; }
    const std::vector<std::vector<double>>& widths() const { return w_; }  // per run, W at each time

private:
    SaturationRule rule_;
    std::vector<double> times_;
    std::vector<std::vector<double>> w_;
    WindowComparison last_;
    double since_ = -1;
};

// The runs of one width L, advanced side by side through
// roughness_sample_counts' times until their ensemble W has saturated by
// `rule` (and t >= min_time), or at the latest to max_time.
struct RoughnessEnsemble {
    int width;                            // L
    std::vector<std::uint64_t> seeds;     // run r's generator seed
    std::vector<double> times;            // t sampled, monolayers, up to the stop (every run the same)
    std::vector<std::vector<double>> w;   // w[r][k]: run r's W at times[k]
    bool saturated;                       // the rule stopped the runs; false: max_time did
    double stop_time;                     // times.back()
    double agreeing_since;                // when the windows began to agree for good, or -1
    WindowComparison check;               // the comparison at the stop
    double saturated_w, saturated_w_sem;  // W over the last window (T/r, T], mean over runs and its standard error
};

// `seeds` runs of width L (3..10,000,000), run r seeded with the r-th output
// of SplitMix64(seed) as roughness_curve does; each run draws exactly what
// it would alone, so only the stop depends on the ensemble.
// min_time <= max_time, both 1..1e9 monolayers.
RoughnessEnsemble roughness_until_saturated(int width, double min_time, double max_time, int points_per_decade,
                                            int seeds, std::uint64_t seed, const SaturationRule& rule);

// The mean W over the ensemble's runs at each sampled time, as roughness_curve averages them.
RoughnessCurve mean_over_runs(const RoughnessEnsemble& ensemble);

}  // namespace sim
