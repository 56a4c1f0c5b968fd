// The site-percolation threshold of the square lattice by Newman & Ziff
// (PRL 85, 4104 (2000)). pc-threshold: R_L(p), the probability that an
// L x L torus wraps at occupation p, for several L from the samples'
// wrapping points (sim/percolation_threshold); the estimate p_c(L) where
// R_L(p) = R_infinity(p_c), and those estimates extrapolated to L = infinity
// along L^(-11/4).
//
// The samples are work items (scenes/work_items.hpp): blocks of samples_per_item
// samples of one L, L after L in the order of `sizes`, each drawing from
// its own stream sim::Random::for_item(seed, item). An L's samples are its
// blocks' in item order, so the figure is the same bits on any number of
// threads, ranks or shards.
#include "sim/percolation_threshold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>

#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/percolation_common.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"

namespace scenes {
namespace {

constexpr int most_sizes = 16;
constexpr int largest_size = 4096;           // sim's bound: N = 2^24 sites
constexpr int most_samples = 100'000'000;    // sim's bound per run
constexpr int most_per_item = 1'000'000;     // an item's result: 8 MB
constexpr long long most_items = 1'000'000;  // parts are files: a million at most
constexpr int curve_points = 161;            // p values a curve is drawn through
constexpr double exponent = sim::threshold_correction_exponent;

// Each criterion: its name in the description, and what the left panel's title says it counts.
struct CriterionInfo {
    sim::WrapCriterion criterion;
    const char* name;
    const char* words;
};
constexpr CriterionInfo criteria[] = {
    {sim::WrapCriterion::one_direction, "one_direction", "a cluster wraps one given way"},
    {sim::WrapCriterion::either_direction, "either_direction", "a cluster wraps either way"},
    {sim::WrapCriterion::both_directions, "both_directions", "a cluster wraps both ways"},
};

const CriterionInfo& info_of(sim::WrapCriterion c) {
    for (const CriterionInfo& i : criteria)
        if (i.criterion == c) return i;
    return criteria[0];  // every enumerator is in the table
}

const char* criterion_name(sim::WrapCriterion c) {
    return info_of(c).name;
}
const char* criterion_words(sim::WrapCriterion c) {
    return info_of(c).words;
}

const std::string sizes_allowed =
    "2 to " + std::to_string(most_sizes) +
    " lattice sizes (two at least, to extrapolate), ascending, each an integer from 2 to " +
    std::to_string(largest_size);

struct Params {
    std::vector<long long> sizes{16, 32, 64, 128};
    int samples = 6000, per_item = 250;
    sim::WrapCriterion criterion = sim::WrapCriterion::one_direction;
    double p_c = 0.59274621;
    std::vector<double> p_range{0.55, 0.64};
};

const Schema<Params> param_schema = [] {
    Schema<Params> s;
    s.key(
        {"sizes", "lattice sizes L (each an L x L torus), ascending", "a list of integers", sizes_allowed},
        [](Settings& section, const std::string& key, Params& p) {
            p.sizes = section.integers(key, p.sizes);
            if (p.sizes.size() < 2 || p.sizes.size() > static_cast<std::size_t>(most_sizes))
                section.refuse(key, sizes_allowed);
            for (std::size_t i = 0; i < p.sizes.size(); ++i)
                if (p.sizes[i] < 2 || p.sizes[i] > largest_size || (i > 0 && p.sizes[i] <= p.sizes[i - 1]))
                    section.refuse(key, sizes_allowed);
        },
        [](const Params& d) { return nlohmann::json(d.sizes); });
    s.count("samples", &Params::samples, "samples per L", 2, most_samples);
    s.count("samples_per_item", &Params::per_item,
            "samples in one work item, a block of one L: what a thread, an MPI rank or a shard computes at once", 1,
            most_per_item);
    std::vector<std::pair<std::string, sim::WrapCriterion>> names;
    for (const CriterionInfo& i : criteria) names.push_back({i.name, i.criterion});
    s.choice("criterion", &Params::criterion, names,
             "what counts as wrapping: one_direction (R^(h), a cluster wraps a given way), either_direction (R^(e)) "
             "or both_directions (R^(b))");
    add_p_c_key(s, &Params::p_c, "the known threshold drawn for reference (Newman & Ziff 2000: 0.59274621)");
    s.key(
        {"p_range",
         "[low, high]: the occupation probabilities of the left panel, where the curves' crossings are sought",
         "a list of numbers", "[low, high] with 0 < low < high < 1"},
        [](Settings& section, const std::string& key, Params& p) {
            p.p_range = section.numbers(key, p.p_range);
            if (p.p_range.size() != 2 || !(p.p_range[0] > 0 && p.p_range[0] < p.p_range[1] && p.p_range[1] < 1))
                section.refuse(key, "[low, high] with 0 < low < high < 1");
        },
        [](const Params& d) { return nlohmann::json(d.p_range); });
    return s;
}();

struct Style {
    std::vector<Colour> colours{colour("#9ecae1"), colour("#4292c6"), colour("#08519c"), colour("#08306b")};
    Colour estimate = colour("#252525"), crossing = colour("#e6550d"), fit = colour("#d62728"),
           reference = colour("#737373");
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"colours", "one colour per L, used in turn", "a list of colours"}, &Style::colours, read_colours)
        .field({"estimate_colour", "colour of the estimates p_c(L) and their error bars", "a colour"}, &Style::estimate,
               read_colour)
        .field({"crossing_colour", "colour of the crossings of successive L's curves", "a colour"}, &Style::crossing,
               read_colour)
        .field({"fit_colour", "colour of the extrapolation line and its intercept", "a colour"}, &Style::fit,
               read_colour)
        .field({"reference_colour", "colour of the reference lines", "a colour"}, &Style::reference, read_colour)
        .part(plot_settings_schema(), &Style::plot);

// Each size as the scene works with it.
std::vector<int> sizes_of(const Params& p) {
    return {p.sizes.begin(), p.sizes.end()};
}

std::vector<glm::vec4> rgba(const std::vector<Colour>& colours) {
    std::vector<glm::vec4> out;
    for (const Colour& c : colours) out.push_back(c.rgba);
    return out;
}

// L^(-11/4): where an estimate at L sits on the extrapolation's axis.
double correction_x(double size) {
    return std::pow(size, -exponent);
}

// What the samples of one L give.
struct SizeResult {
    int size;
    std::vector<sim::WrappingPoints> points;
    sim::ThresholdEstimate estimate;
    std::vector<double> curve;  // R_L(p) at the curve's p values
};

// Where the curves of sizes[i] and sizes[i + 1] cross, if they do in p_range.
struct Crossing {
    int size_a, size_b;
    std::optional<double> p;
    double x;  // drawn at the pair's geometric mean L: (L_a L_b)^(-11/8)
};

class PercolationThresholdScene : public SceneBase, public WorkItems {
public:
    PercolationThresholdScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          sizes_(sizes_of(p_)),
          colours_(rgba(s_.colours)),
          plot_style_(plot_style(s_.plot, options.scale)) {
        refuse_steps(d, "the plot shows the samples' wrapping curves and estimates, not steps", true);
        const long long items = static_cast<long long>(sizes_.size()) * blocks();
        if (items > most_items)
            params_.refuse("samples_per_item",
                           "an integer from 1 to " + std::to_string(most_per_item) + " giving at most " +
                               std::to_string(most_items) + " work items (" + std::to_string(sizes_.size()) +
                               " sizes x samples / samples_per_item; it would give " + std::to_string(items) + ")");
    }

    // Per thread running an item, the largest L's lattice (a union-find site
    // of 16 bytes and an order entry of 4 per site) and its block's points
    // four times over (the vector, its CBOR array, the part's bytes and
    // their copy as written); every L's wrapping points, 8 bytes a sample,
    // twice (the items' results, then the L's points decoded from them,
    // held for the curves and crossings); the binomial convolution's tables
    // of the largest L, two at once (a crossing), 16 bytes a site each.
    std::vector<MemoryNeed> memory() const override {
        const double largest = sizes_.back();
        const double threads = options_.threads;
        return {grid_need("a lattice of the largest L per thread", largest, largest, 20, threads),
                {"a block's points per thread, four copies", 4.0 * 8 * p_.per_item * threads},
                {"the wrapping points of every sample, as results and decoded",
                 2.0 * 8 * static_cast<double>(p_.samples) * static_cast<double>(sizes_.size())},
                grid_need("binomial convolution tables of the largest L", largest, largest, 16, 2)};
    }

    const WorkItems* work() const override { return this; }
    int item_count() const override { return static_cast<int>(sizes_.size()) * blocks(); }
    std::string item_name(int item) const override {
        const int first = (item % blocks()) * p_.per_item;
        return "L = " + std::to_string(size_of(item)) + ", samples " + std::to_string(first) + " to " +
               std::to_string(first + samples_in(item) - 1);
    }
    // Two CBOR byte strings of 4 bytes a sample, their keys and headers.
    double item_bytes() const override { return 8.0 * p_.per_item + 64; }

    nlohmann::json run_item(int item) const override {
        sim::Random rng = sim::Random::for_item(d_.seed, static_cast<std::uint64_t>(item));
        const std::vector<sim::WrappingPoints> points = sim::wrapping_points(size_of(item), samples_in(item), rng);
        std::vector<std::uint32_t> horizontal, vertical;
        horizontal.reserve(points.size());
        vertical.reserve(points.size());
        for (const sim::WrappingPoints& w : points) {
            horizontal.push_back(w.horizontal);
            vertical.push_back(w.vertical);
        }
        return {{"horizontal", binary_of<std::uint32_t>(horizontal)}, {"vertical", binary_of<std::uint32_t>(vertical)}};
    }

    // Each sample wrapped after occupying 1 to L^2 sites, each way.
    void check_result(int item, const nlohmann::json& r) const override {
        namespace rc = result_check;
        const double sites = double(size_of(item)) * size_of(item);
        const std::size_t count = static_cast<std::size_t>(samples_in(item));
        rc::values_in<std::uint32_t>(rc::member(r, "horizontal"), "horizontal", count, 1, sites);
        rc::values_in<std::uint32_t>(rc::member(r, "vertical"), "vertical", count, 1, sites);
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, item_count());
        std::vector<nlohmann::json> results = out.results(*this);
        std::vector<SizeResult> sizes = decode(results);
        const std::vector<double> ps = curve_ps();
        try {
            for (SizeResult& r : sizes) {
                r.estimate = sim::threshold_from_wrapping(r.points, r.size, p_.criterion);
                r.curve = sim::wrapping_probability(r.points, r.size, p_.criterion, ps);
            }
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(d_.id + ": " + e.what());
        }
        const std::vector<Crossing> crossings = cross(sizes);
        const sim::ThresholdExtrapolation fit = extrapolate(sizes);
        out.figure(
            plot_figure({curves_axes(sizes, ps), extrapolation_axes(sizes, crossings, fit)}, d_, options_,
                        plot_style_),
            metadata(sizes, ps, crossings, fit));
        progress.finish();
    }

private:
    int blocks() const { return (p_.samples + p_.per_item - 1) / p_.per_item; }
    int size_of(int item) const { return sizes_[static_cast<std::size_t>(item / blocks())]; }
    int samples_in(int item) const { return std::min(p_.per_item, p_.samples - (item % blocks()) * p_.per_item); }

    // Every L's points, its blocks' in item order; each result is released as it is read.
    std::vector<SizeResult> decode(std::vector<nlohmann::json>& results) const {
        std::vector<SizeResult> sizes;
        for (std::size_t i = 0; i < sizes_.size(); ++i) {
            SizeResult r{sizes_[i], {}, {}, {}};
            r.points.reserve(static_cast<std::size_t>(p_.samples));
            for (int b = 0; b < blocks(); ++b) {
                const int item = static_cast<int>(i) * blocks() + b;
                nlohmann::json& result = results[static_cast<std::size_t>(item)];
                const std::size_t count = static_cast<std::size_t>(samples_in(item));
                const std::vector<std::uint32_t> h = values_of<std::uint32_t>(result.at("horizontal"), count),
                                                 v = values_of<std::uint32_t>(result.at("vertical"), count);
                for (std::size_t s = 0; s < count; ++s) r.points.push_back({h[s], v[s]});
                result = nullptr;
            }
            sizes.push_back(std::move(r));
        }
        return sizes;
    }

    // The left panel's p values, evenly spaced over p_range.
    std::vector<double> curve_ps() const {
        std::vector<double> ps;
        for (int i = 0; i < curve_points; ++i)
            ps.push_back(p_.p_range[0] + (p_.p_range[1] - p_.p_range[0]) * i / (curve_points - 1));
        return ps;
    }

    std::vector<Crossing> cross(const std::vector<SizeResult>& sizes) const {
        std::vector<Crossing> crossings;
        for (std::size_t i = 0; i + 1 < sizes.size(); ++i) {
            const SizeResult &a = sizes[i], &b = sizes[i + 1];
            crossings.push_back(
                {a.size, b.size,
                 sim::wrapping_crossing(a.points, a.size, b.points, b.size, p_.criterion, p_.p_range[0], p_.p_range[1]),
                 correction_x(std::sqrt(double(a.size) * b.size))});
        }
        return crossings;
    }

    sim::ThresholdExtrapolation extrapolate(const std::vector<SizeResult>& sizes) const {
        std::vector<sim::ThresholdEstimate> estimates;
        for (const SizeResult& r : sizes) estimates.push_back(r.estimate);
        try {
            return sim::extrapolate_threshold(estimates);
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(d_.id + ": no extrapolation: " + e.what());
        }
    }

    // R_L(p) for each L over p_range, the level R_infinity(p_c) dashed and
    // the reference p_c as a thin vertical line.
    render::Axes curves_axes(const std::vector<SizeResult>& sizes, const std::vector<double>& ps) const {
        const double level = sim::wrapping_probability_at_threshold(p_.criterion);
        render::Axes axes;
        axes.x_label = "occupation probability p";
        axes.y_label = "wrapping probability R_L(p)";
        axes.title = std::string("R_L(p): ") + criterion_words(p_.criterion);
        axes.x_range = std::pair{p_.p_range[0], p_.p_range[1]};
        axes.y_range = std::pair{-0.03, 1.03};
        axes.legend = render::Legend::upper_left;
        for (std::size_t i = 0; i < sizes.size(); ++i)
            axes.series.push_back(line_series(ps, sizes[i].curve, "L = " + std::to_string(sizes[i].size),
                                              colours_[i % colours_.size()], 2.0f, false));
        axes.series.push_back(line_series({p_.p_range[0], p_.p_range[1]}, {level, level},
                                          "R\u221e(p_c) = " + format_fixed(level, 5), s_.reference.rgba, 1.5f, true));
        axes.reference_lines.push_back({render::Direction::vertical, p_.p_c, s_.reference.rgba, 1.0f, {}});
        return axes;
    }

    // The estimates p_c(L) with their error bars and the crossings against
    // L^(-11/4) (in units of a power of ten, as matplotlib's offset), the
    // weighted line and its intercept, the reference dashed.
    render::Axes extrapolation_axes(const std::vector<SizeResult>& sizes, const std::vector<Crossing>& crossings,
                                    const sim::ThresholdExtrapolation& fit) const {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const double largest_x = correction_x(sizes.front().size);
        const int power = static_cast<int>(std::floor(std::log10(largest_x)));
        const double unit = std::pow(10.0, power);
        std::vector<double> x, y, bar_x, bar_y;
        for (const SizeResult& r : sizes) {
            const double at = correction_x(r.size) / unit, p = r.estimate.p_c, e = r.estimate.standard_error;
            x.push_back(at);
            y.push_back(p);
            bar_x.insert(bar_x.end(), {at, at, nan});
            bar_y.insert(bar_y.end(), {p - e, p + e, nan});
        }
        std::vector<double> cross_x, cross_y;
        for (const Crossing& c : crossings)
            if (c.p) {
                cross_x.push_back(c.x / unit);
                cross_y.push_back(*c.p);
            }
        const double right = 1.08 * largest_x / unit, left = -0.04 * largest_x / unit;
        render::Axes axes;
        axes.x_label = "L\u207b\u00b9\u00b9\u2044\u2074 (\u00d7" + render::power_of_ten_label(power) + ")";
        axes.y_label = "estimate of p_c";
        axes.title = "extrapolation to L = \u221e";
        axes.x_range = std::pair{left, right};
        axes.y_range = extrapolation_y_range(sizes, cross_y, fit);
        axes.legend = render::Legend::upper_right;
        axes.series = {
            line_series({left, right}, {p_.p_c, p_.p_c}, "reference", s_.reference.rgba, 1.5f, true),
            line_series({0.0, right}, {fit.p_c, fit.p_c + fit.slope * right * unit}, "weighted fit", s_.fit.rgba, 1.8f,
                        false),
            line_series({0.0, 0.0}, {fit.p_c - fit.standard_error, fit.p_c + fit.standard_error}, "", s_.fit.rgba, 1.8f,
                        false),
            dot_series({0.0}, {fit.p_c}, "", s_.fit.rgba, 7.0f),
            line_series(bar_x, bar_y, "", s_.estimate.rgba, 1.5f, false),
            dot_series(x, y, "p_c(L) \u00b1 1 s.e.", s_.estimate.rgba, 7.0f),
        };
        if (!cross_x.empty())
            axes.series.push_back(dot_series(cross_x, cross_y, "curve crossings", s_.crossing.rgba, 6.0f));
        axes.notes = {{"p_c = " + format_fixed(fit.p_c, 5) + " \u00b1 " + format_fixed(fit.standard_error, 5),
                       {0.04f, 0.91f},
                       render::Align::left},
                      {"reference " + format_fixed(p_.p_c, 8), {0.04f, 0.84f}, render::Align::left}};
        return axes;
    }

    // Everything drawn, with a tenth of the span below and as much again
    // above for the legend and the notes, side by side.
    std::pair<double, double> extrapolation_y_range(const std::vector<SizeResult>& sizes,
                                                    const std::vector<double>& cross_y,
                                                    const sim::ThresholdExtrapolation& fit) const {
        double low = std::min(p_.p_c, fit.p_c - fit.standard_error),
               high = std::max(p_.p_c, fit.p_c + fit.standard_error);
        for (const SizeResult& r : sizes) {
            low = std::min(low, r.estimate.p_c - r.estimate.standard_error);
            high = std::max(high, r.estimate.p_c + r.estimate.standard_error);
        }
        for (double p : cross_y) low = std::min(low, p), high = std::max(high, p);
        const double span = high - low;
        return {low - 0.1 * span, high + span};
    }

    nlohmann::json metadata(const std::vector<SizeResult>& sizes, const std::vector<double>& ps,
                            const std::vector<Crossing>& crossings, const sim::ThresholdExtrapolation& fit) const {
        // The plotted numbers: the p values and every curve, each L's
        // estimate and error, the crossings (NaN where none), the fit.
        std::vector<double> plotted(ps);
        nlohmann::json per_size = nlohmann::json::array();
        for (const SizeResult& r : sizes) {
            plotted.insert(plotted.end(), r.curve.begin(), r.curve.end());
            plotted.insert(plotted.end(), {double(r.size), r.estimate.p_c, r.estimate.standard_error});
            per_size.push_back({{"L", r.size},
                                {"samples", r.estimate.samples},
                                {"p_c", r.estimate.p_c},
                                {"standard_error", r.estimate.standard_error},
                                {"L^(-11/4)", correction_x(r.size)}});
        }
        nlohmann::json crossing_list = nlohmann::json::array();
        for (const Crossing& c : crossings) {
            plotted.push_back(c.p.value_or(std::numeric_limits<double>::quiet_NaN()));
            crossing_list.push_back({{"sizes", {c.size_a, c.size_b}},
                                     {"p", c.p ? nlohmann::json(*c.p) : nlohmann::json()},
                                     {"drawn_at_L^(-11/4)", c.x}});
        }
        plotted.insert(plotted.end(), {fit.p_c, fit.standard_error, fit.slope});
        return {{"params", params_.used()},
                {"style", style_.used()},
                {"criterion", criterion_name(p_.criterion)},
                {"R_infinity_at_p_c", sim::wrapping_probability_at_threshold(p_.criterion)},
                {"work_items", {{"count", item_count()}, {"samples_per_item", p_.per_item}}},
                {"estimates", per_size},
                {"crossings", crossing_list},
                {"extrapolation",
                 {{"p_c", fit.p_c},
                  {"standard_error", fit.standard_error},
                  {"slope", fit.slope},
                  {"slope_error", fit.slope_error},
                  {"chi_squared", fit.chi_squared},
                  {"degrees_of_freedom", fit.degrees_of_freedom},
                  {"exponent", exponent},
                  {"weights", "1 / standard_error^2 of each L's estimate"}}},
                {"p_c_reference", p_.p_c},
                {"deviation_in_standard_errors", (fit.p_c - p_.p_c) / fit.standard_error},
                {"state_sha256", state_hash(plotted)}};
    }

    const Params p_;
    const Style s_;
    const std::vector<int> sizes_;
    const std::vector<glm::vec4> colours_;
    const render::PlotStyle plot_style_;
};

std::unique_ptr<Scene> read_percolation_threshold(const Description& d, const SceneOptions& options) {
    return std::make_unique<PercolationThresholdScene>(d, options);
}

}  // namespace

SceneInfo percolation_threshold_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"percolation_threshold",
            read_percolation_threshold,
            {},
            {
                {"/extrapolation/p_c",
                 "p_c, extrapolated",
                 "number",
                 "",
                 {{"", "0.59274621(13) (Newman & Ziff 2000)"}},
                 "",
                 "standard_error"},
                {"/deviation_in_standard_errors", "from the reference", "number", "standard errors", {}, "", "", 2},
                {"/estimates/*/p_c", "p_c(L), L = {L}", "number", "", {{"", "0.59274621"}}, "", "standard_error"},
                {"/extrapolation/chi_squared", "chi squared of the fit", "number", "", {}, "", "", 3},
                {"/extrapolation/degrees_of_freedom", "degrees of freedom", "integer", ""},
            }};
}

}  // namespace scenes
