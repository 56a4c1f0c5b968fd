// Percolation's phase change (Think Complexity 2e, section 7.4). tc7-phase:
// P(percolating cluster) against q, and find_critical's walk towards the
// critical q.
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/percolation_common.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"

namespace scenes {
namespace {

constexpr double most_q_values = 10000;

// What [first, last, step] allows for qs.
const std::string qs_allowed = "[first, last, step] with 0 <= first <= last <= 1 and 0 < step <= 1, at most " +
                               std::to_string(int(most_q_values)) + " values";

struct Params {
    int n = 100, trials = 100;
    std::vector<double> qs_range{0.50, 0.70, 0.01};
    std::vector<double> qs;  // the q values tried, from qs_range
    double walk_start = 0.6, walk_step = 0.005;
    int iterations = 100;
    double p_c = 0.59274621;
};

const Schema<Params> params_read =
    Schema<Params>()
        .count("n", &Params::n, "array size", 2, 4096)
        .count("trials", &Params::trials, "runs per q", 1, 100000)
        .key({"qs", "[first, last, step] of the q values tried", "a list of numbers", qs_allowed,
              nlohmann::json({0.50, 0.70, 0.01})},
             [](Settings& s, const std::string& key, Params& p) {
                 const auto range = s.numbers(key, p.qs_range);
                 if (range.size() != 3 || !(range[0] >= 0 && range[0] <= range[1] && range[1] <= 1) ||
                     !(range[2] > 0 && range[2] <= 1))
                     s.refuse(key, qs_allowed);
                 // Computed from an integer count so 0.55, 0.60, 0.65 come out as written.
                 const double steps = std::floor((range[1] - range[0]) / range[2] + 1e-9);
                 if (steps + 1 > most_q_values) s.refuse(key, qs_allowed);
                 const int count = static_cast<int>(steps) + 1;
                 for (int i = 0; i < count; ++i) p.qs.push_back(std::round((range[0] + i * range[2]) * 1e9) / 1e9);
             })
        .number("walk_start", &Params::walk_start, "find_critical's first q", 0.0, 1.0)
        .number("walk_step", &Params::walk_step, "find_critical's step in q", 1e-6, 0.5)
        .count("walk_iterations", &Params::iterations, "find_critical's runs", 1, 100000);

const Schema<Params> param_schema = [] {
    Schema<Params> s = params_read;
    add_p_c_key(s, &Params::p_c, "the known threshold drawn for reference (Newman & Ziff 2000)");
    return s;
}();

struct Style {
    Colour series = colour("#619aca"), reference = colour("#526e97");
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"series_colour", "colour of the measured curves", "a colour"}, &Style::series, read_colour)
        .field({"reference_colour", "colour of the reference lines", "a colour"}, &Style::reference, read_colour)
        .part(plot_settings_schema(), &Style::plot);

// The sweep's numbers: per q, the fraction of trials that percolated.
struct Sweep {
    std::vector<double> probability;
    nlohmann::json table = nlohmann::json::array();
};

// find_critical's walk: every q visited, its index and mean.
struct Walk {
    std::vector<double> q, index;
    double mean;
};

// Work items: one a q value (its trials), then find_critical's walk; each
// draws from its own stream, sim::Random::for_item(seed, item).
class PercolationPhaseScene : public SceneBase, public WorkItems {
public:
    PercolationPhaseScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          plot_style_(plot_style(s_.plot, options.scale)) {}

    // One run at a time: its cells, a byte each, and as much again for
    // its wet fronts (the cells wetted in one step, a small share of the
    // grid: tc7-phase at n = 4096 peaked 17 MiB over the program).
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("a run's cells and wet fronts", p_.n, p_.n, 2, 1)};
    }

    const WorkItems* work() const override { return this; }
    int item_count() const override { return static_cast<int>(p_.qs.size()) + 1; }
    std::string item_name(int item) const override {
        return item < walk_item() ? "q = " + format_fixed(p_.qs[item], 4) : "find_critical's walk";
    }
    double item_bytes() const override { return 64 + 9.0 * p_.iterations; }
    nlohmann::json run_item(int item) const override {
        sim::Random rng = sim::Random::for_item(d_.seed, static_cast<std::uint64_t>(item));
        if (item == walk_item())
            return {{"walk", sim::find_critical(p_.n, p_.walk_start, p_.walk_step, p_.iterations, rng)}};
        int percolating = 0;
        for (int t = 0; t < p_.trials; ++t) percolating += test_perc(p_.n, p_.qs[item], rng).percolates;
        return {{"percolating", percolating}};
    }

    // A count of percolating trials of this q, or the walk: its start and a
    // q a run, each a probability.
    void check_result(int item, const nlohmann::json& r) const override {
        namespace rc = result_check;
        if (item < walk_item()) {
            rc::integer_in(rc::member(r, "percolating"), "percolating", 0, p_.trials);
            return;
        }
        for (const nlohmann::json& q : rc::array_of(rc::member(r, "walk"), "walk", p_.iterations + 1LL))
            rc::number_in(q, "walk", 0, 1);
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, item_count());
        const std::vector<nlohmann::json> results = out.results(*this);
        const Sweep sweep = sweep_q(results);
        const Walk walk = walk_of(results[walk_item()].at("walk").get<std::vector<double>>());
        // The plotted numbers: the q values, their fractions percolating, then the walk.
        std::vector<double> plotted(p_.qs);
        plotted.insert(plotted.end(), sweep.probability.begin(), sweep.probability.end());
        plotted.insert(plotted.end(), walk.q.begin(), walk.q.end());
        nlohmann::json meta = {
            {"params", params_.used()},
            {"style", style_.used()},
            {"probability", sweep.table},
            {"walk", walk.q},
            {"walk_mean", walk.mean},
            {"p_c", p_.p_c},
            {"state_sha256", state_hash(plotted)},
        };
        out.figure(plot_figure({phase_axes(sweep), walk_axes(walk)}, d_, options_, plot_style_),
                   meta);
        progress.finish();
    }

private:
    int walk_item() const { return static_cast<int>(p_.qs.size()); }

    Sweep sweep_q(const std::vector<nlohmann::json>& results) const {
        Sweep sweep;
        for (std::size_t i = 0; i < p_.qs.size(); ++i) {
            const int percolating = results[i].at("percolating").get<int>();
            sweep.probability.push_back(double(percolating) / p_.trials);
            sweep.table.push_back({{"q", p_.qs[i]}, {"probability", sweep.probability.back()}});
        }
        return sweep;
    }

    Walk walk_of(std::vector<double> q) const {
        if (q.size() != static_cast<std::size_t>(p_.iterations) + 1)  // the start, then a q a run
            throw std::runtime_error("find_critical's result holds " + std::to_string(q.size()) + " of " +
                                     std::to_string(p_.iterations + 1) + " values");
        Walk walk;
        walk.q = std::move(q);
        for (std::size_t i = 0; i < walk.q.size(); ++i) walk.index.push_back(double(i));
        walk.mean = std::accumulate(walk.q.begin(), walk.q.end(), 0.0) / double(walk.q.size());
        return walk;
    }

    // The fraction percolating against q, p_c dashed, and the book's quoted
    // numbers as notes.
    render::Axes phase_axes(const Sweep& sweep) const {
        render::Axes phase;
        phase.x_label = "q";
        phase.y_label = "Fraction percolating";
        phase.y_range = std::pair{-0.05, 1.05};
        phase.legend = render::Legend::lower_right;
        phase.series = {
            line_series({p_.p_c, p_.p_c}, {-0.05, 1.05}, "p_c = " + format_fixed(p_.p_c, 4), s_.reference.rgba, 1.5f,
                        true),
            line_series(p_.qs, sweep.probability, std::to_string(p_.trials) + " runs of n = " + std::to_string(p_.n),
                        s_.series.rgba, 2.0f, false),
            dot_series(p_.qs, sweep.probability, "", s_.series.rgba, 6.0f)};
        // The book's three quoted numbers, when those q values were tried.
        for (double quoted : {0.55, 0.60, 0.65})
            for (std::size_t i = 0; i < p_.qs.size(); ++i)
                if (std::abs(p_.qs[i] - quoted) < 1e-9)
                    phase.notes.push_back(
                        {"P(" + format_fixed(quoted, 2) + ") = " + format_fixed(sweep.probability[i], 2),
                         {0.04f, 0.86f - 0.08f * float(phase.notes.size())},
                         render::Align::left});
        return phase;
    }

    // The walk's q against its iteration, and its mean dashed.
    render::Axes walk_axes(const Walk& walk) const {
        render::Axes axes;
        axes.x_label = "Iteration";
        axes.y_label = "q";
        axes.legend = render::Legend::upper_right;
        axes.series = {line_series(walk.index, walk.q, "find_critical walk", s_.series.rgba, 1.5f, false),
                       line_series({0, double(p_.iterations)}, {walk.mean, walk.mean},
                                   "mean " + format_fixed(walk.mean, 4), s_.reference.rgba, 1.5f, true)};
        return axes;
    }

    const Params p_;
    const Style s_;
    const render::PlotStyle plot_style_;
};

std::unique_ptr<Scene> read_percolation_phase(const Description& d, const SceneOptions& options) {
    return std::make_unique<PercolationPhaseScene>(d, options);
}

}  // namespace

SceneInfo percolation_phase_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"percolation_phase",
            read_percolation_phase,
            {},
            {
                {"/walk_mean",
                 "find_critical mean q",
                 "number",
                 "",
                 {{"", "about 0.59 (book); p_c = 0.59274621 (Newman & Ziff 2000)"}}},
                {"/probability/*/probability",
                 "P(percolating), q = {q}",
                 "number",
                 "",
                 {{"q=0.55", "about 0 (book)"}, {"q=0.6", "about 0.7 (book)"}, {"q=0.65", "about 1 (book)"}},
                 "q=0.55|0.6|0.65"},
            }};
}

}  // namespace scenes
