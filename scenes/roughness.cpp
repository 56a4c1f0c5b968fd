// Ballistic deposition's roughness ("Ballistic deposition in Python"): the
// interface width W(L, t) for several L, with the fitted KPZ-class exponents
// beta (growth, on the last L) and alpha (W at saturation against L). The
// runs of one L stop together once their ensemble W has saturated
// (sim::SaturationRule), so the time goes where the figure needs it rather
// than to a fixed multiple of L^1.5.
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"
#include "sim/deposition.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

// A run's last time, monolayers: what sim::roughness_curve accepts.
constexpr double longest_run = 1e9;

struct Params {
    std::vector<long long> widths{100, 200, 500, 1000, 2000};
    int seeds = 4;
    double factor = 3.0;
    int per_decade = 10;
    std::vector<double> beta_range{2, 50};
    sim::SaturationRule rule{3.0, 2.0, 2.0, 3};
};

const Schema<Params> param_schema = [] {
    using R = sim::SaturationRule;
    Schema<R> rule;
    rule.number("saturation_window", &R::window,
                "r: at each sample time T the runs' mean W over (T/r, T] is compared with their mean over (T/r^2, "
                "T/r]");
    rule.number("saturation_tolerance", &R::tolerance,
                "the two windows agree when their means differ by less than this many standard errors (from the "
                "spread of the runs' own differences)");
    rule.number("saturation_hold", &R::hold,
                "an L's runs stop once the windows have agreed at every sample for this factor in time; W_sat is the "
                "runs' mean W over the last window, (T/r, T] at the stop");
    rule.count("saturation_samples", &R::min_samples, "samples each window needs before the two are compared");
    rule.check(validated<R>({{"window", "saturation_window"},
                             {"tolerance", "saturation_tolerance"},
                             {"hold", "saturation_hold"},
                             {"min_samples", "saturation_samples"}}));
    Schema<Params> s;
    s.key(
        {"widths", "system sizes L", "a list of integers",
         "system sizes, each an integer from 8 to 100000, two different at least"},
        [](Settings& section, const std::string& key, Params& p) {
            p.widths = section.integers(key, p.widths);
            for (long long w : p.widths)
                if (w < 8 || w > 100000) section.refuse(key, "system sizes, each an integer from 8 to 100000");
            // Two different sizes at least: alpha is the slope of W_sat against L.
            if (p.widths.size() < 2 ||
                std::adjacent_find(p.widths.begin(), p.widths.end(), std::not_equal_to<>()) == p.widths.end())
                section.refuse(key, "two different sizes at least, to fit alpha");
        },
        [](const Params& d) { return nlohmann::json(d.widths); });
    s.count("seeds", &Params::seeds, "runs averaged per L", 1, 1000);
    s.number("saturation_factor", &Params::factor,
             "the bound: an L's runs stop at t = factor * L^1.5 monolayers at the latest, saturated or not (KPZ: "
             "saturation at L^z, z = 3/2)",
             0.01, 100);
    s.count("points_per_decade", &Params::per_decade, "W samples per decade of t", 1, 100);
    s.key(
        {"beta_range", "[t1, t2]: growth-regime times fitted for beta, monolayers; no run stops before t2",
         "a list of numbers", "[t1, t2] with 0 < t1 < t2"},
        [](Settings& section, const std::string& key, Params& p) {
            p.beta_range = section.numbers(key, p.beta_range);
            if (p.beta_range.size() != 2 || !(p.beta_range[1] > p.beta_range[0]) || p.beta_range[0] <= 0)
                section.refuse(key, "[t1, t2] with 0 < t1 < t2");
        },
        [](const Params& d) { return nlohmann::json(d.beta_range); });
    s.part(rule, &Params::rule);
    return s;
}();

struct Style {
    std::vector<Colour> colours{colour("#c6dbef"), colour("#6baed6"), colour("#2171b5"), colour("#08519c"),
                                colour("#08306b")};
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"colours", "one colour per L", "a list of colours"}, &Style::colours, read_colours)
        .part(plot_settings_schema(), &Style::plot);

// SHA-256 of the sampled times and every run's W, run by run: the whole
// state the figure is drawn from.
std::string runs_hash(const sim::RoughnessEnsemble& e) {
    std::vector<double> values = e.times;
    for (const auto& run : e.w) values.insert(values.end(), run.begin(), run.end());
    return state_hash(values);
}

nlohmann::json number_json(double x) {  // JSON has no infinity: +-inf as text
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(x > 0 ? "inf" : "-inf");
}

nlohmann::json window_json(std::size_t samples, double mean, double sem) {
    return {{"samples", samples}, {"mean_w", mean}, {"sem_w", sem}};
}

// An L's stop and the rule's numbers at it.
nlohmann::json stop_json(const sim::RoughnessEnsemble& e) {
    const sim::WindowComparison& c = e.check;
    return {{"stop_time", e.stop_time},
            {"stop_time_over_L1.5", e.stop_time / std::pow(double(e.width), 1.5)},
            {"saturated", e.saturated},
            {"agreeing_since", e.agreeing_since},
            {"previous_window", window_json(c.previous_samples, c.previous_mean, c.previous_sem)},
            {"last_window", window_json(c.last_samples, c.last_mean, c.last_sem)},
            {"difference", c.difference},
            {"difference_sem", c.difference_sem},
            {"z", number_json(c.z)}};
}

// What the runs measured: per L its saturated W and curve, and the last L's
// growth regime.
struct Measured {
    std::vector<double> sizes, saturated;
    nlohmann::json curves = nlohmann::json::array();
    std::vector<double> beta_t, beta_w;
};

const glm::vec4 fit_colour = {0.85f, 0.33f, 0.1f, 1};

// An L's ensemble as its work item's result, and back: every number
// exactly (CBOR keeps a double's bits), the runs' W as arrays of doubles.
nlohmann::json ensemble_json(const sim::RoughnessEnsemble& e) {
    const sim::WindowComparison& c = e.check;
    nlohmann::json w = nlohmann::json::array();
    for (const std::vector<double>& run : e.w) w.push_back(binary_of<double>(run));
    return {{"width", e.width},
            {"seeds", e.seeds},
            {"times", binary_of<double>(e.times)},
            {"w", w},
            {"saturated", e.saturated},
            {"stop_time", e.stop_time},
            {"agreeing_since", e.agreeing_since},
            {"check",
             {c.compared, c.previous_samples, c.last_samples, c.previous_mean, c.previous_sem, c.last_mean,
              c.last_sem, c.difference, c.difference_sem, c.z, c.agree}},
            {"saturated_w", e.saturated_w},
            {"saturated_w_sem", e.saturated_w_sem}};
}

sim::RoughnessEnsemble ensemble_of(const nlohmann::json& j, int width, int runs) {
    sim::RoughnessEnsemble e;
    e.width = j.at("width").get<int>();
    e.seeds = j.at("seeds").get<std::vector<std::uint64_t>>();
    const nlohmann::json& times = j.at("times");
    e.times = values_of<double>(times, times.is_binary() ? times.get_binary().size() / sizeof(double) : 0);
    for (const nlohmann::json& run : j.at("w")) e.w.push_back(values_of<double>(run, e.times.size()));
    if (e.width != width || e.w.size() != static_cast<std::size_t>(runs) || e.seeds.size() != e.w.size())
        throw std::runtime_error("the result for L = " + std::to_string(width) + " holds another ensemble");
    e.saturated = j.at("saturated").get<bool>();
    e.stop_time = j.at("stop_time").get<double>();
    e.agreeing_since = j.at("agreeing_since").get<double>();
    const nlohmann::json& c = j.at("check");
    e.check = {c.at(0).get<bool>(),   c.at(1).get<std::size_t>(), c.at(2).get<std::size_t>(),
               c.at(3).get<double>(), c.at(4).get<double>(),      c.at(5).get<double>(),
               c.at(6).get<double>(), c.at(7).get<double>(),      c.at(8).get<double>(),
               c.at(9).get<double>(), c.at(10).get<bool>()};
    e.saturated_w = j.at("saturated_w").get<double>();
    e.saturated_w_sem = j.at("saturated_w_sem").get<double>();
    return e;
}

// Work items: one an L, its runs side by side (their stop is the ensemble's).
class RoughnessScene : public SceneBase, public WorkItems {
public:
    RoughnessScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          widths_(p_.widths.begin(), p_.widths.end()),
          plot_style_(plot_style(s_.plot, options.scale)) {
        check_run_lengths();
        check_beta_times();
    }

    const WorkItems* work() const override { return this; }
    int item_count() const override { return static_cast<int>(widths_.size()); }
    std::string item_name(int item) const override { return "L = " + std::to_string(widths_[item]); }
    // The runs' W at every sampled time: points_per_decade a decade up to the longest run, as doubles.
    double item_bytes() const override {
        const double samples =
            p_.per_decade * (std::log10(run_length(*std::max_element(widths_.begin(), widths_.end()))) + 2);
        return 9.0 * samples * (p_.seeds + 1) + 12.0 * p_.seeds + 1024;
    }
    // L's runs are seeded from seed + item (the item's index), as before items.
    nlohmann::json run_item(int item) const override {
        const int L = widths_[item];
        const double max_time = run_length(L), min_time = std::min(p_.beta_range[1], max_time);
        return ensemble_json(sim::roughness_until_saturated(L, min_time, max_time, p_.per_decade, p_.seeds,
                                                            d_.seed + static_cast<std::uint64_t>(item), p_.rule));
    }

    // An ensemble of this L and runs, its times increasing up to the stop
    // within the run's length, every W and statistic finite (z may be
    // infinite: a difference without spread).
    void check_result(int item, const nlohmann::json& r) const override {
        namespace rc = result_check;
        const int L = widths_[static_cast<std::size_t>(item)];
        const double max_time = run_length(L);
        if (rc::integer_in(rc::member(r, "width"), "width", 1, 10000000) != L)
            throw std::invalid_argument("it is the ensemble of another L than " + std::to_string(L));
        for (const nlohmann::json& s : rc::array_of(rc::member(r, "seeds"), "seeds", p_.seeds))
            if (!s.is_number_unsigned()) throw std::invalid_argument("seeds holds a value that is not a seed");
        const nlohmann::json& t = rc::member(r, "times");
        const std::size_t samples = t.is_binary() ? t.get_binary().size() / sizeof(double) : 0;
        if (samples == 0) throw std::invalid_argument("times holds no sampled time");
        const std::vector<double> times = rc::values_in<double>(t, "times", samples, 0, max_time);
        for (std::size_t k = 1; k < times.size(); ++k)
            if (!(times[k] > times[k - 1])) throw std::invalid_argument("times do not increase at " + std::to_string(k));
        for (const nlohmann::json& run : rc::array_of(rc::member(r, "w"), "w", p_.seeds))
            rc::values_in<double>(run, "w", samples, 0, std::numeric_limits<double>::max());
        rc::boolean(rc::member(r, "saturated"), "saturated");
        if (rc::number_in(rc::member(r, "stop_time"), "stop_time", 0, max_time) != times.back())
            throw std::invalid_argument("stop_time is not the last sampled time");
        rc::number_in(rc::member(r, "agreeing_since"), "agreeing_since", -1, max_time);
        const nlohmann::json& c = rc::array_of(rc::member(r, "check"), "check", 11);
        const double huge = std::numeric_limits<double>::max();
        rc::boolean(c[0], "check.compared");
        rc::integer_in(c[1], "check.previous_samples", 0, static_cast<long long>(samples));
        rc::integer_in(c[2], "check.last_samples", 0, static_cast<long long>(samples));
        for (int i : {3, 5}) rc::number_in(c[i], "check.mean", 0, huge);
        for (int i : {4, 6, 8}) rc::number_in(c[i], "check.sem", 0, huge);
        rc::number_in(c[7], "check.difference", -huge, huge);
        if (!c[9].is_number() || std::isnan(c[9].get<double>())) throw std::invalid_argument("check.z is not a number");
        rc::boolean(c[10], "check.agree");
        rc::number_in(rc::member(r, "saturated_w"), "saturated_w", 0, huge);
        rc::number_in(rc::member(r, "saturated_w_sem"), "saturated_w_sem", 0, huge);
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(widths_.size()));
        const std::vector<nlohmann::json> results = out.results(*this);
        render::Axes growth = growth_axes();
        Measured m;
        for (std::size_t i = 0; i < widths_.size(); ++i) {
            const int L = widths_[i];
            const double max_time = run_length(L);
            const sim::RoughnessEnsemble runs = ensemble_of(results[i], L, p_.seeds);
            const sim::RoughnessCurve curve = sim::mean_over_runs(runs);
            const glm::vec4 colour = s_.colours[i % s_.colours.size()].rgba;
            growth.series.push_back(
                line_series(curve.times, curve.mean_w, "L = " + std::to_string(L), colour, 1.8f, false));
            record(curve, runs, max_time, i + 1 == widths_.size(), m);
        }
        if (m.beta_t.size() < 2) throw std::logic_error(d_.id + ": beta_range holds fewer than two sampled times");
        const sim::LineFit beta = sim::fit_log_log(m.beta_t, m.beta_w);
        const sim::LineFit alpha = sim::fit_log_log(m.sizes, m.saturated);
        const std::vector<double> beta_line = sim::power_law(beta, m.beta_t);
        growth.series.push_back(
            line_series(m.beta_t, beta_line, "fit, beta = " + format_fixed(beta.slope, 3), fit_colour, 2.2f, true));
        growth.notes.push_back({"KPZ: beta = 1/3", {0.62f, 0.10f}, render::Align::left});
        out.figure(plot_figure({growth, scaling_axes(m, alpha)}, d_, options_, plot_style_),
                   metadata(m, beta, alpha));
        progress.finish();
    }

private:
    double run_length(int L) const { return p_.factor * std::pow(double(L), 1.5); }

    // Every run must be one sim::roughness_until_saturated accepts: 1 to 1e9 monolayers.
    void check_run_lengths() {
        for (int L : widths_)
            if (const double t = run_length(L); !(t >= 1 && t <= longest_run))
                params_.refuse("saturation_factor", "a factor giving runs of 1 to " + description::shown(longest_run) +
                                                        " monolayers, factor * L^1.5 (L = " + std::to_string(L) +
                                                        " would run " + description::shown(t) + ")");
    }

    // beta is fitted on the last L's samples inside beta_range: two at least.
    // No run stops before beta_range's end, so every run has them.
    void check_beta_times() {
        const int L = widths_.back();
        int inside = 0;
        for (std::uint64_t n : sim::roughness_sample_counts(L, run_length(L), p_.per_decade)) {
            const double t = static_cast<double>(n) / L;  // as roughness_curve's times
            inside += t >= p_.beta_range[0] && t <= p_.beta_range[1];
        }
        if (inside < 2)
            params_.refuse("beta_range",
                           "[t1, t2] with 0 < t1 < t2 holding two sampled times at least (L = " + std::to_string(L) +
                               " is sampled from 1 to " + description::shown(run_length(L)) + " monolayers, " +
                               std::to_string(p_.per_decade) + " times a decade)");
    }

    // Adds one L: its saturated W (the runs' mean over the last window at
    // the stop), its growth regime when it is the last, its metadata with
    // the stop and every run's seed.
    void record(const sim::RoughnessCurve& curve, const sim::RoughnessEnsemble& runs, double max_time, bool last,
                Measured& m) const {
        m.sizes.push_back(curve.width);
        m.saturated.push_back(runs.saturated_w);
        if (last) {
            for (std::size_t k = 0; k < curve.times.size(); ++k)
                if (curve.times[k] >= p_.beta_range[0] && curve.times[k] <= p_.beta_range[1]) {
                    m.beta_t.push_back(curve.times[k]);
                    m.beta_w.push_back(curve.mean_w[k]);
                }
        }
        m.curves.push_back({{"width", curve.width},
                            {"seeds", p_.seeds},
                            {"run_seeds", runs.seeds},
                            {"max_time", max_time},
                            {"stop", stop_json(runs)},
                            {"times", curve.times},
                            {"mean_w", curve.mean_w},
                            {"sem_w", curve.sem_w},
                            {"saturated_w", runs.saturated_w},
                            {"saturated_w_sem", runs.saturated_w_sem},
                            {"state_sha256", runs_hash(runs)}});
    }

    static render::Axes growth_axes() {
        render::Axes growth;
        growth.x_scale = growth.y_scale = render::Scale::log;
        growth.x_label = "t (monolayers)";
        growth.y_label = "W(L, t)";
        growth.legend = render::Legend::upper_left;
        return growth;
    }

    // W at saturation against L, and alpha's fit.
    render::Axes scaling_axes(const Measured& m, const sim::LineFit& alpha) const {
        render::Axes scaling;
        scaling.x_scale = scaling.y_scale = render::Scale::log;
        scaling.x_label = "L";
        scaling.y_label = "saturated W";
        scaling.legend = render::Legend::upper_left;
        const std::vector<double> alpha_line = sim::power_law(alpha, m.sizes);
        scaling.series = {
            dot_series(m.sizes, m.saturated, "W_sat, last window at the stop", {0.03f, 0.19f, 0.42f, 1},
                       8.0f),
            line_series(m.sizes, alpha_line, "fit, alpha = " + format_fixed(alpha.slope, 3), fit_colour, 2.0f, true)};
        scaling.notes.push_back({"KPZ: alpha = 1/2", {0.62f, 0.10f}, render::Align::left});
        return scaling;
    }

    nlohmann::json metadata(const Measured& m, const sim::LineFit& beta, const sim::LineFit& alpha) const {
        return {
            {"params", params_.used()},
            {"style", style_.used()},
            {"saturation_rule",
             {{"rule",
               "an L's runs advance side by side; at each sample time T (t >= beta_range's end) each run's "
               "mean W over (T/r, T] and over (T/r^2, T/r] is taken; the windows agree when the mean over "
               "runs of (last - previous) is below tolerance times its standard error across runs; all runs "
               "of that L stop once they have agreed at every sample since T/hold, or at "
               "saturation_factor * L^1.5; W_sat is the mean over runs of the last window, its error the "
               "standard error across runs"},
              {"window", p_.rule.window},
              {"tolerance", p_.rule.tolerance},
              {"hold", p_.rule.hold},
              {"min_samples", p_.rule.min_samples},
              {"max_factor", p_.factor}}},
            {"curves", m.curves},
            {"beta", {{"value", beta.slope}, {"fit_range", p_.beta_range}, {"width", widths_.back()}, {"r", beta.r}}},
            {"alpha", {{"value", alpha.slope}, {"widths", m.sizes}, {"saturated_w", m.saturated}, {"r", alpha.r}}}};
    }

    const Params p_;
    const Style s_;
    const std::vector<int> widths_;
    const render::PlotStyle plot_style_;
};

std::unique_ptr<Scene> read_roughness(const Description& d, const SceneOptions& options) {
    return std::make_unique<RoughnessScene>(d, options);
}

}  // namespace

SceneInfo roughness_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"roughness",
            read_roughness,
            {},
            {
                {"/beta/value",
                 "growth exponent beta",
                 "number",
                 "",
                 {{"", "1/3 (KPZ); about 0.30 at L <= 2000 (published)"}}},
                {"/beta/fit_range", "beta fitted over t", "range", "monolayers"},
                {"/beta/width", "beta fitted at L", "integer", ""},
                {"/alpha/value", "roughness exponent alpha", "number", "", {{"", "1/2 (KPZ)"}}},
                {"/alpha/widths", "alpha fitted over L", "range", ""},
            }};
}

}  // namespace scenes
