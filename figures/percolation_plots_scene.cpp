// Percolation's numbers (Think Complexity 2e, section 7.4 and Fig 7.9): the
// cluster's size against the array's, the probability of percolating against
// q, and the random walk that finds the critical q.
#include <cmath>
#include <numeric>

#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "sim/check.hpp"
#include "sim/fractal.hpp"
#include "sim/percolation.hpp"
#include "sim/random.hpp"

namespace figures {
namespace {

// The book's test_perc on a fresh n x n model drawn from `rng`.
sim::PercolationRun test_perc(int n, double q, sim::Random& rng, long* wet = nullptr) {
    sim::PercolationParams p;
    p.n = n;
    p.q = q;
    sim::Percolation model(p, rng);
    const auto run = sim::run_to_bottom_or_fixed_point(model);
    if (wet) *wet = model.wet_count();
    return run;
}

}  // namespace

// tc7-9: cells in the percolating cluster against array size, at q near critical.
void render_percolation_scaling(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"q", "probability that a cell is porous"},
                     {"sizes", "[first, last]: every array size in between is tried once"}});
    Settings style("style", d.style,
                   with_plot_style_keys({{"d2_colour", "colour of the size^2 line"},
                                         {"dots_colour", "colour of the cluster sizes"},
                                         {"d1_colour", "colour of the size line"},
                                         {"line_width", "reference line width, pixels at scale 1"},
                                         {"marker_size", "dot diameter, pixels at scale 1"}}));
    double q = 0;
    int first = 0, last = 0;
    try {
        q = params.number("q", 0.59);
        sim::require_number("q", q, 0.0, 1.0);
        const auto sizes = params.integers("sizes", {10, 100});
        if (sizes.size() != 2) throw std::invalid_argument("sizes must be [first, last]");
        sim::require_integer("sizes[0]", sizes[0], 2, 4096);
        sim::require_integer("sizes[1]", sizes[1], sizes[0], 4096);
        first = static_cast<int>(sizes[0]);
        last = static_cast<int>(sizes[1]);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    progress.start(d.id, last - first + 1);
    sim::Random rng(d.seed);
    std::vector<double> kept, squares, filled;
    for (int size = first; size <= last; ++size) {
        long wet = 0;
        if (test_perc(size, q, rng, &wet).percolates) {
            kept.push_back(size);
            squares.push_back(double(size) * size);
            filled.push_back(double(wet - size));  // the book: num_wet minus the initial top row
        }
        progress.advance();
    }
    if (kept.size() < 2) throw std::runtime_error(d.id + ": fewer than two runs percolated; no slope to fit");
    const sim::LineFit fit = sim::fit_log_log(kept, filled);
    // The plotted numbers: the sizes that percolated, then their cluster cells.
    std::vector<double> plotted(kept);
    plotted.insert(plotted.end(), filled.begin(), filled.end());

    const float width = static_cast<float>(style.number("line_width", 3.0));
    render::Axes axes;
    axes.x_scale = axes.y_scale = render::Scale::log;
    axes.x_range = std::pair{9.0, 110.0};
    axes.y_range = std::pair{9.0, 20000.0};
    axes.x_label = "Array Size";
    axes.y_label = "Cell Count";
    axes.legend = render::Legend::upper_left;
    axes.series = {line_series(kept, squares, "d=2", style_colour(style, "d2_colour", "#526e97"), width, false),
                   dot_series(kept, filled, "filled", style_colour(style, "dots_colour", "#4f80b8"),
                              static_cast<float>(style.number("marker_size", 5.0))),
                   line_series(kept, kept, "d=1", style_colour(style, "d1_colour", "#7ab2d7"), width, false)};
    nlohmann::json meta = {
        {"params", params.used()},
        {"style", style.used()},
        {"runs", last - first + 1},
        {"percolating_runs", kept.size()},
        {"sizes", kept},
        {"cluster_cells", filled},
        {"slope", fit.slope},
        {"intercept", fit.intercept},
        {"r", fit.r},
        {"state_sha256", state_hash(plotted)},
    };
    write_figure(d, options,
                 draw_plot_row({axes}, figure_width(d, options), figure_height(d, options),
                               read_plot_style(style, options.scale)),
                 meta);
    progress.finish();
}

// tc7-phase: P(percolating cluster) against q, and find_critical's walk.
void render_percolation_phase(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"n", "array size"},
                     {"trials", "runs per q"},
                     {"qs", "[first, last, step] of the q values tried"},
                     {"walk_start", "find_critical's first q"},
                     {"walk_step", "find_critical's step in q"},
                     {"walk_iterations", "find_critical's runs"},
                     {"p_c", "the known threshold drawn for reference (Newman & Ziff 2000)"}});
    Settings style("style", d.style,
                   with_plot_style_keys({{"series_colour", "colour of the measured curves"},
                                         {"reference_colour", "colour of the reference lines"}}));
    int n = 0, trials = 0, iterations = 0;
    double walk_start = 0, walk_step = 0, p_c = 0;
    std::vector<double> qs;
    try {
        n = params.count("n", 100);
        sim::require_integer("n", n, 2, 4096);
        trials = params.count("trials", 100);
        sim::require_integer("trials", trials, 1, 100000);
        const auto range = params.numbers("qs", {0.50, 0.70, 0.01});
        if (range.size() != 3 || !(range[2] > 0) || range[1] < range[0])
            throw std::invalid_argument("qs must be [first, last, step] with first <= last and step > 0");
        sim::require_number("qs first", range[0], 0.0, 1.0);
        sim::require_number("qs last", range[1], 0.0, 1.0);
        // Computed from an integer count so 0.55, 0.60, 0.65 come out as written.
        const int count = static_cast<int>(std::floor((range[1] - range[0]) / range[2] + 1e-9)) + 1;
        sim::require_integer("number of q values", count, 1, 10000);
        for (int i = 0; i < count; ++i) qs.push_back(std::round((range[0] + i * range[2]) * 1e9) / 1e9);
        walk_start = params.number("walk_start", 0.6);
        sim::require_number("walk_start", walk_start, 0.0, 1.0);
        walk_step = params.number("walk_step", 0.005);
        sim::require_number("walk_step", walk_step, 1e-6, 0.5);
        iterations = params.count("walk_iterations", 100);
        sim::require_integer("walk_iterations", iterations, 1, 100000);
        p_c = params.number("p_c", 0.59274621);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    progress.start(d.id, static_cast<long long>(qs.size()) * trials + iterations);
    sim::Random rng(d.seed);  // one stream: the trials in order of q, then the walk

    std::vector<double> probability;
    nlohmann::json table = nlohmann::json::array();
    for (double q : qs) {
        int percolating = 0;
        for (int t = 0; t < trials; ++t) {
            percolating += test_perc(n, q, rng).percolates;
            progress.advance();
        }
        probability.push_back(double(percolating) / trials);
        table.push_back({{"q", q}, {"probability", probability.back()}});
    }
    const std::vector<double> walk = sim::find_critical(n, walk_start, walk_step, iterations, rng);
    std::vector<double> index;
    for (std::size_t i = 0; i < walk.size(); ++i) index.push_back(double(i));
    progress.advance(iterations);
    const double mean = std::accumulate(walk.begin(), walk.end(), 0.0) / double(walk.size());
    // The plotted numbers: the q values, their fractions percolating, then the walk.
    std::vector<double> plotted(qs);
    plotted.insert(plotted.end(), probability.begin(), probability.end());
    plotted.insert(plotted.end(), walk.begin(), walk.end());

    const glm::vec4 colour = style_colour(style, "series_colour", "#619aca");
    const glm::vec4 reference = style_colour(style, "reference_colour", "#526e97");
    render::Axes phase;
    phase.x_label = "q";
    phase.y_label = "Fraction percolating";
    phase.y_range = std::pair{-0.05, 1.05};
    phase.legend = render::Legend::lower_right;
    phase.series = {
        line_series({p_c, p_c}, {-0.05, 1.05}, "p_c = " + format_fixed(p_c, 4), reference, 1.5f, true),
        line_series(qs, probability, std::to_string(trials) + " runs of n = " + std::to_string(n), colour, 2.0f, false),
        dot_series(qs, probability, "", colour, 6.0f)};
    render::Axes walk_axes;
    walk_axes.x_label = "Iteration";
    walk_axes.y_label = "q";
    walk_axes.legend = render::Legend::upper_right;
    walk_axes.series = {
        line_series(index, walk, "find_critical walk", colour, 1.5f, false),
        line_series({0, double(iterations)}, {mean, mean}, "mean " + format_fixed(mean, 4), reference, 1.5f, true)};
    // The book's three quoted numbers, when those q values were tried.
    for (double quoted : {0.55, 0.60, 0.65})
        for (std::size_t i = 0; i < qs.size(); ++i)
            if (std::abs(qs[i] - quoted) < 1e-9)
                phase.notes.push_back({"P(" + format_fixed(quoted, 2) + ") = " + format_fixed(probability[i], 2),
                                       {0.04f, 0.86f - 0.08f * float(phase.notes.size())},
                                       render::Align::left});

    nlohmann::json meta = {
        {"params", params.used()}, {"style", style.used()},
        {"probability", table},    {"walk", walk},
        {"walk_mean", mean},       {"p_c", p_c},
        {"state_sha256", state_hash(plotted)},
    };
    write_figure(d, options,
                 draw_plot_row({phase, walk_axes}, figure_width(d, options), figure_height(d, options),
                               read_plot_style(style, options.scale)),
                 meta);
    progress.finish();
}

}  // namespace figures
