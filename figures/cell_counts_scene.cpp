// On cells against time on log-log axes, one panel per rule (Think
// Complexity 2e, Fig 7.7): the box-counting estimate of a 1-D CA's dimension.
#include <cmath>

#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "sim/cell1d.hpp"
#include "sim/check.hpp"
#include "sim/fractal.hpp"

namespace figures {

void render_cell_counts(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"rules", "Wolfram rule numbers, one panel each"},
                     {"n", "rows of each CA; counts are taken at i = 1 .. n-1 (the book's count_cells)"},
                     {"boundary", "\"zero\" or \"wrap\""}});
    Settings style("style", d.style,
                   with_plot_style_keys({{"d2_colour", "colour of the y = i^2 line"},
                                         {"series_colour", "colour of the rule's counts"},
                                         {"d1_colour", "colour of the y = i line"},
                                         {"line_width", "line width in pixels at scale 1"}}));
    std::vector<int> rules;
    int n = 0;
    sim::Boundary boundary;
    try {
        for (long long r : params.integers("rules", {20, 50, 18})) {
            sim::require_integer("rules", r, 0, 255);
            rules.push_back(static_cast<int>(r));
        }
        n = params.count("n", 500);
        sim::require_integer("n", n, 3, 100000);
        boundary = sim::parse_boundary(params.text("boundary", "zero"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (rules.empty()) throw UsageError(d.id + ": params.rules is empty");
    const glm::vec4 d2 = style_colour(style, "d2_colour", "#526e97");
    const glm::vec4 series = style_colour(style, "series_colour", "#619aca");
    const glm::vec4 d1 = style_colour(style, "d1_colour", "#96c5e1");
    const float width = static_cast<float>(style.number("line_width", 2.0));
    progress.start(d.id, static_cast<long long>(rules.size()));

    std::vector<render::Axes> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    std::vector<double> steps, squares;
    for (int i = 1; i < n; ++i) {
        steps.push_back(i);
        squares.push_back(double(i) * i);
    }
    for (int rule : rules) {
        const std::vector<long> counts = sim::count_cells(rule, n, boundary);
        const std::vector<double> cells(counts.begin(), counts.end());
        const sim::LineFit fit = sim::fit_log_log(steps, cells);
        render::Axes axes;
        axes.x_scale = axes.y_scale = render::Scale::log;
        axes.x_range = std::pair{1.0, 600.0};  // the book's xlim
        axes.x_label = "Time Steps";
        if (panels.empty()) axes.y_label = "Number of Cells";
        axes.legend = render::Legend::upper_left;
        axes.series = {line_series(steps, squares, "d=2", d2, width, true),
                       line_series(steps, cells, "rule=" + std::to_string(rule), series, width, false),
                       line_series(steps, steps, "d=1", d1, width, true)};
        panels.push_back(std::move(axes));
        panel_meta.push_back({{"rule", rule},
                              {"steps", n - 1},
                              {"statistics", {{"on_cells", counts.back()}}},
                              {"slope", fit.slope},
                              {"intercept", fit.intercept},
                              {"r", fit.r},
                              {"state_sha256", state_hash(cells)}});
        progress.advance();
    }
    write_figure(d, options,
                 draw_plot_row(panels, figure_width(d, options), figure_height(d, options),
                               read_plot_style(style, options.scale)),
                 {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}});
    progress.finish();
}

}  // namespace figures
