#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/deposition.hpp"
#include "sim/fractal.hpp"
#include "sim/random.hpp"

using sim::Deposition;
using sim::DepositionParams;

TEST_CASE("deposition: each particle sticks at max(h[i-1], h[i]+1, h[i+1]) of the heights before it",
          "[deposition]") {
    // An independent replay: the same stream, one below(L) per particle, periodic neighbours by modulo.
    const int L = 37;
    const std::uint64_t seed = 9;
    Deposition model(DepositionParams{L, 20000, true}, seed);
    sim::Random reference(seed);
    std::vector<std::int64_t> h(L, 0);
    for (int k = 0; k < 20000; ++k) {
        model.drop();
        const int i = static_cast<int>(reference.below(L));
        h[i] = std::max({h[(i + L - 1) % L], h[i] + 1, h[(i + 1) % L]});
        REQUIRE(model.heights() == h);
    }
    CHECK(model.dropped() == 20000);
    const auto particles = model.particles();
    REQUIRE(particles.size() == 20000);
    // Arrival order: replaying once more, particle k sits where the k-th drop put it.
    sim::Random again(seed);
    std::vector<std::int64_t> g(L, 0);
    for (std::uint64_t k = 0; k < 20000; ++k) {
        const int i = static_cast<int>(again.below(L));
        g[i] = std::max({g[(i + L - 1) % L], g[i] + 1, g[(i + 1) % L]});
        REQUIRE(particles[k].arrival == k);
        REQUIRE(particles[k].column == i);
        REQUIRE(particles[k].height == g[i]);
    }
}

TEST_CASE("deposition: one particle per cell, as many cells as particles, every cell stuck to an earlier one",
          "[deposition]") {
    // The post's sticking rule read on the deposit itself: a particle rests on
    // the floor, or on an earlier particle below it, or beside an earlier one
    // (left or right, wrapping) at the same height.
    const int L = 64;
    Deposition model(DepositionParams{L, 30000, true}, 4);
    model.drop(30000);
    CHECK(model.cells() == 30000);
    const auto particles = model.particles();
    REQUIRE(particles.size() == model.cells());
    std::int64_t top = 0;
    for (const auto& p : particles) top = std::max(top, p.height);
    // arrival + 1 per cell, 0 for a hole.
    std::vector<std::uint64_t> cell(static_cast<std::size_t>(L) * (top + 1), 0);
    auto at = [&](int column, std::int64_t height) -> std::uint64_t& {
        return cell[static_cast<std::size_t>(height) * L + static_cast<std::size_t>((column + L) % L)];
    };
    for (const auto& p : particles) {
        REQUIRE(p.column >= 0);
        REQUIRE(p.column < L);
        REQUIRE(p.height >= 1);
        REQUIRE(at(p.column, p.height) == 0);  // no two particles share a cell
        at(p.column, p.height) = p.arrival + 1;
    }
    std::int64_t holes = 0;
    for (const auto& p : particles) {
        const std::uint64_t me = p.arrival + 1;
        auto earlier = [&](int column, std::int64_t height) {
            const std::uint64_t other = at(column, height);
            return other != 0 && other < me;
        };
        const bool stuck = p.height == 1 || earlier(p.column, p.height - 1) || earlier(p.column - 1, p.height) ||
                           earlier(p.column + 1, p.height);
        INFO("particle " << p.arrival << " at column " << p.column << " height " << p.height);
        REQUIRE(stuck);
        // Nothing arrived later below it in its own column: the fall is blocked by what is there.
        if (p.height > 1) REQUIRE(at(p.column, p.height - 1) < me);
        holes += p.height > 1 && at(p.column, p.height - 1) == 0;
    }
    CHECK(holes > 1000);  // ballistic deposits are porous (density about 0.47)
    for (int c = 0; c < L; ++c) {
        std::int64_t highest = 0;
        for (std::int64_t y = 1; y <= top; ++y)
            if (at(c, y)) highest = y;
        REQUIRE(model.heights()[c] == highest);
    }
}

TEST_CASE("deposition: mean height and roughness are the mean and population deviation of the heights",
          "[deposition]") {
    Deposition model(DepositionParams{50, 0, true}, 2);
    CHECK(model.mean_height() == 0);
    CHECK(model.roughness() == 0);
    model.drop(5000);
    double sum = 0, squares = 0;
    for (std::int64_t h : model.heights()) sum += static_cast<double>(h);
    const double mean = sum / 50;
    for (std::int64_t h : model.heights()) squares += (h - mean) * (h - mean);
    CHECK(model.mean_height() == Approx(mean).epsilon(1e-12));
    CHECK(model.roughness() == Approx(std::sqrt(squares / 50)).epsilon(1e-12));
    CHECK(model.mean_height() > 5000 / 50);  // holes lift the surface above one cell per particle
}

TEST_CASE("deposition: W grows like t^beta with beta near 1/3 and saturates like L^alpha", "[deposition]") {
    // Growth: L = 1000 over t = 2..100 monolayers, 4 runs. Effective BD values
    // at these sizes sit below the KPZ 1/3 (published: about 0.30).
    const auto growth = sim::roughness_curve(1000, 100, 10, 4, 2025);
    std::vector<double> t, w;
    for (std::size_t k = 0; k < growth.times.size(); ++k)
        if (growth.times[k] >= 2 && growth.times[k] <= 100) {
            t.push_back(growth.times[k]);
            w.push_back(growth.mean_w[k]);
        }
    REQUIRE(t.size() == 17);  // 10^0.4 .. 10^2
    const double beta = sim::fit_log_log(t, w).slope;
    INFO("beta = " << beta);
    CHECK(beta > 0.2);
    CHECK(beta < 0.4);

    // Saturation: W at t = 10 L^1.5 and 20 L^1.5 agree (the crossover is
    // near L^1.5; growth at t^beta would add 2^0.3 - 1 = 23%), and across
    // L = 16, 32, 64 the saturated W, averaged over t in [10, 20] L^1.5,
    // grows like L^alpha: KPZ 1/2, effectively about 0.43 at these sizes.
    std::vector<double> sizes, saturated;
    for (int L : {16, 32, 64}) {
        const double t_sat = 10 * std::pow(L, 1.5);
        const auto curve = sim::roughness_curve(L, 2 * t_sat, 20, 60, 7);
        auto nearest = [&](double time) {  // index of the sample nearest in log t
            std::size_t best = 0;
            for (std::size_t k = 0; k < curve.times.size(); ++k)
                if (std::abs(std::log(curve.times[k] / time)) < std::abs(std::log(curve.times[best] / time)))
                    best = k;
            return best;
        };
        const std::size_t first = nearest(t_sat), last = nearest(2 * t_sat);
        const double w1 = curve.mean_w[first], w2 = curve.mean_w[last];
        const double se = std::hypot(curve.sem_w[first], curve.sem_w[last]);
        INFO("L = " << L << " W(10 L^1.5) = " << w1 << ", W(20 L^1.5) = " << w2 << ", standard error " << se);
        CHECK(std::abs(w1 - w2) < 5 * se);
        CHECK(w2 / w1 < 1.15);
        double window = 0;
        for (std::size_t k = first; k <= last; ++k) window += curve.mean_w[k];
        sizes.push_back(L);
        saturated.push_back(window / static_cast<double>(last - first + 1));
    }
    const double alpha = sim::fit_log_log(sizes, saturated).slope;
    INFO("alpha = " << alpha);
    CHECK(alpha > 0.3);
    CHECK(alpha < 0.6);
}

TEST_CASE("deposition: the same seed gives the same heights, another seed differs", "[deposition]") {
    Deposition a(DepositionParams{200, 40000, true}, 5), b(DepositionParams{200, 40000, false}, 5),
        c(DepositionParams{200, 40000, true}, 6);
    a.drop(40000);
    b.drop(40000);  // not recording changes nothing but the store
    c.drop(40000);
    CHECK(a.heights() == b.heights());
    CHECK(a.heights() != c.heights());
    CHECK(b.cells() == 0);
    CHECK_THROWS_AS(b.particles(), std::logic_error);
    const auto r1 = sim::roughness_curve(100, 50, 5, 3, 1), r2 = sim::roughness_curve(100, 50, 5, 3, 1);
    CHECK(r1.mean_w == r2.mean_w);
    CHECK(r1.sem_w == r2.sem_w);
}

TEST_CASE("deposition: roughness_curve samples 10^(k/ppd) monolayers, whole particles", "[deposition]") {
    const auto curve = sim::roughness_curve(10, 100, 4, 1, 3);
    const std::vector<double> expected{1.0, 1.8, 3.2, 5.6, 10.0, 17.8, 31.6, 56.2, 100.0};
    REQUIRE(curve.times.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) CHECK(curve.times[k] == Approx(expected[k]).epsilon(1e-12));
    CHECK(curve.width == 10);
    CHECK(curve.sem_w == std::vector<double>(expected.size(), 0.0));
    // One run: mean_w is that run's W, replayed from the seed SplitMix64 gives it.
    sim::SplitMix64 seeds(3);
    Deposition run(DepositionParams{10, 0, false}, seeds.next());
    run.drop(1000);
    CHECK(curve.mean_w.back() == run.roughness());
}

TEST_CASE("deposition rejects bad parameters with messages naming them", "[deposition]") {
    auto message_of = [](DepositionParams p) {
        try {
            p.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(message_of(DepositionParams{}) == "accepted");
    CHECK(message_of(DepositionParams{2, 100, true}) ==
          "width = 2 is not allowed: an integer from 3 to 10000000");
    CHECK(message_of(DepositionParams{500, 5000000000ULL, true}) ==
          "particles = 5000000000 is not allowed: an integer from 0 to 4294967295");
    CHECK_THROWS_AS(Deposition(DepositionParams{0, 0, true}, 1), std::invalid_argument);
    CHECK_THROWS_WITH(sim::roughness_curve(100, 0.5, 10, 1, 1),
                      "max_time = 0.5 is not allowed: a number from 1 to 1e+09");
    CHECK_THROWS_WITH(sim::roughness_curve(100, 10, 10, 0, 1),
                      "seeds = 0 is not allowed: an integer from 1 to 1000000");
    CHECK_THROWS_WITH(sim::roughness_curve(100, 10, 0, 1, 1),
                      "points_per_decade = 0 is not allowed: an integer from 1 to 1000");
}

namespace {

// An ensemble's W at t = 1, 10^0.1, 10^0.2, ... (10 a decade) for `samples`
// samples, run r's from `w_of(t, k, r)`; the sample at which the detector
// first said saturated, or -1.
template <class W>
int feed(sim::SaturationDetector& detector, int runs, int samples, W w_of) {
    int stopped_at = -1;
    std::vector<double> w(static_cast<std::size_t>(runs));
    for (int k = 0; k < samples; ++k) {
        const double t = std::pow(10.0, k / 10.0);
        for (int r = 0; r < runs; ++r) w[static_cast<std::size_t>(r)] = w_of(t, k, r);
        if (detector.add(t, w) && stopped_at < 0) stopped_at = k;
    }
    return stopped_at;
}

double wiggle(int k, int r) { return (k + r) % 3 == 0 ? 0.4 : -0.2; }  // mean zero over any 3 samples

}  // namespace

TEST_CASE("saturation rule on an ensemble: a flat W stops where expected, a growing one never", "[deposition]") {
    const sim::SaturationRule rule;  // r = 3, 2 standard errors, held for a factor 2, 3 samples a window
    // Four runs on different levels with a wiggle of period 3 out of phase.
    // First comparison at t = 10^0.7: (10^0.7 / 9, 10^0.7 / 3] holds t = 1,
    // 10^0.1, 10^0.2, its 3 samples. The runs' differences scatter around 0,
    // so the windows agree from there; the hold needs t >= 2 x 10^0.7 = 10.02,
    // which 10^1.0 misses: the stop is sample 11.
    sim::SaturationDetector flat(rule, 4);
    CHECK(feed(flat, 4, 30, [](double, int k, int r) { return 10.0 + r + wiggle(k, r); }) == 11);
    CHECK(flat.last().compared);
    CHECK(flat.last().previous_samples == 5);  // (10^2.9 / 9, 10^2.9 / 3]: 10^2.0 .. 10^2.4
    CHECK(flat.last().last_samples == 5);
    CHECK(flat.last().last_mean == Approx(11.5).margin(0.2));  // the levels' mean, 10 + 1.5
    CHECK(flat.last().last_sem == Approx(std::sqrt(5.0 / 3 / 4)).margin(0.1));  // the levels' spread across runs
    CHECK(std::abs(flat.last().z) < rule.tolerance);
    CHECK(flat.agreeing_since() == Approx(std::pow(10.0, 0.7)));
    // A single run has no spread across runs: only an exactly equal pair agrees.
    sim::SaturationDetector one(rule, 1);
    CHECK(feed(one, 1, 20, [](double, int, int) { return 4.0; }) == 11);
    CHECK(one.last().z == 0);
    // Growing as t^0.3 on run-dependent prefactors: every run's last window
    // is 39% above its previous one, so the paired differences sit many
    // standard errors above 0 for five decades.
    sim::SaturationDetector growing(rule, 4);
    CHECK(feed(growing, 4, 50,
               [](double t, int k, int r) { return (1 + 0.3 * r) * std::pow(t, 0.3) + 0.05 * wiggle(k, r); }) == -1);
    CHECK(growing.last().z > rule.tolerance);
    CHECK(growing.agreeing_since() == -1);
    // Growth that saturates at t = 1000: no stop until the previous window,
    // (T/9, T/3], starts past the plateau's corner at a factor hold later.
    sim::SaturationDetector crossover(rule, 4);
    const int stop = feed(crossover, 4, 60, [](double t, int k, int r) {
        return (1 + 0.3 * r) * std::pow(std::min(t, 1000.0), 0.3) + 0.05 * wiggle(k, r);
    });
    INFO("crossover stopped at sample " << stop);
    CHECK(stop > 30);  // past the corner
    CHECK(stop <= 30 + 9 + 3 + 1);  // the windows clear of it (a factor 9, 9.5 samples) and held a factor 2 (3 samples)
}

TEST_CASE("saturation rule: ensemble windows, paired differences, refusals", "[deposition]") {
    const std::vector<double> t{1, 2, 3, 4, 5, 6, 7, 8};
    // Two runs. T = 8: the last window (8/2, 8] holds t = 5..8, the one before (2, 4] holds 3, 4.
    const std::vector<std::vector<double>> w{{1, 1, 1, 2, 2, 4, 4, 4}, {9, 9, 3, 3, 5, 5, 5, 5}};
    sim::SaturationRule rule;
    rule.window = 2;
    rule.min_samples = 2;
    const auto c = sim::compare_windows(t, w, rule);
    REQUIRE(c.compared);
    CHECK(c.last_samples == 4);
    CHECK(c.previous_samples == 2);
    // Per run: previous 1.5 and 3, last 3.5 and 5, differences 2 and 2.
    CHECK(c.previous_mean == Approx(2.25));
    CHECK(c.previous_sem == Approx(0.75));  // sample deviation 1.06 / sqrt(2)
    CHECK(c.last_mean == Approx(4.25));
    CHECK(c.last_sem == Approx(0.75));
    CHECK(c.difference == Approx(2));
    CHECK(c.difference_sem == 0);  // both runs grew alike: the spread of the windows is between runs, not growth noise
    CHECK(c.z == HUGE_VAL);
    CHECK_FALSE(c.agree);
    rule.min_samples = 3;
    CHECK_FALSE(sim::compare_windows(t, w, rule).compared);
    const std::vector<std::vector<double>> short_run{{1, 2}};
    CHECK_THROWS_AS(sim::compare_windows(t, short_run, rule), std::invalid_argument);
    rule = {};
    rule.window = 1;
    CHECK_THROWS_WITH(sim::SaturationDetector(rule, 4), "window = 1 is not allowed: a number from 1.1 to 100");
    rule = {};
    rule.tolerance = 0;
    CHECK_THROWS_AS(sim::SaturationDetector(rule, 4), std::invalid_argument);
    CHECK_THROWS_WITH(sim::SaturationDetector(sim::SaturationRule{}, 0),
                      "runs = 0 is not allowed: an integer from 1 to 1000000");
    sim::SaturationDetector detector(sim::SaturationRule{}, 2);
    const std::vector<double> two{1, 1}, three{1, 1, 1};
    detector.add(2, two);
    CHECK_THROWS_AS(detector.add(2, two), std::invalid_argument);
    CHECK_THROWS_AS(detector.add(3, three), std::invalid_argument);
}

TEST_CASE("roughness ensembles stop where the same seed stopped them, bit for bit, with each run's own draws",
          "[deposition]") {
    const sim::SaturationRule rule;
    const auto a = sim::roughness_until_saturated(64, 20, 3 * 512, 10, 4, 99, rule);
    const auto b = sim::roughness_until_saturated(64, 20, 3 * 512, 10, 4, 99, rule);
    REQUIRE(a.w.size() == 4);
    CHECK(a.seeds == b.seeds);
    CHECK(a.times == b.times);
    CHECK(a.w == b.w);
    CHECK(a.saturated_w == b.saturated_w);
    CHECK(a.saturated_w_sem == b.saturated_w_sem);
    CHECK(a.stop_time == a.times.back());
    CHECK(a.stop_time >= 20);  // min_time
    CHECK(a.saturated);
    CHECK(a.stop_time < 3 * 512);  // at L = 64 W saturates near t = 50, long before 3 L^1.5
    CHECK(a.saturated_w == a.check.last_mean);
    CHECK(a.saturated_w_sem > 0);
    // Side by side changes no run's draws: run r replays alone from
    // SplitMix64(99)'s r-th output, as roughness_curve seeds it.
    sim::SplitMix64 seeds(99);
    for (std::size_t r = 0; r < 4; ++r) {
        const std::uint64_t s = seeds.next();
        CHECK(a.seeds[r] == s);
        Deposition alone(DepositionParams{64, 0, false}, s);
        alone.drop(static_cast<std::uint64_t>(std::llround(a.stop_time * 64)));
        CHECK(a.w[r].back() == alone.roughness());
    }
    const auto c = sim::roughness_until_saturated(64, 20, 3 * 512, 10, 4, 100, rule);
    CHECK(c.w[0] != a.w[0]);
    // The mean curve averages every run at every sampled time.
    const auto curve = sim::mean_over_runs(a);
    CHECK(curve.times == a.times);
    CHECK(curve.mean_w[0] == Approx((a.w[0][0] + a.w[1][0] + a.w[2][0] + a.w[3][0]) / 4));
    // A bound below saturation (and before the hold could end, at 2 x 10^0.7):
    // the runs stop at its last sample, unsaturated.
    const auto bounded = sim::roughness_until_saturated(64, 1, 10, 10, 4, 99, rule);
    CHECK_FALSE(bounded.saturated);
    CHECK(bounded.stop_time == 10);
    CHECK(bounded.agreeing_since == -1);
}
