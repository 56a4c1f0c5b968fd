// Think Complexity 2e, exercise 7.1: which elementary CAs are fractal? The
// cell-count slope (the box-counting dimension of section 7.5) of all 256
// rules, without and with wrapping, and a gallery of those whose slope is
// not an integer.
#include <cmath>

#include "figures/field_spec.hpp"
#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "render/digest.hpp"
#include "sim/cell1d.hpp"
#include "sim/check.hpp"
#include "sim/fractal.hpp"

namespace figures {
namespace {

// The slope over i >= fit_from: the first rows are a transient that tilts a
// fit over all of them (a rule filling whole rows has counts 1, 1002, 2003,
// ..., a line of slope 1 whose first point alone pulls the fit to 1.1).
double slope_of(int rule, int n, sim::Boundary boundary, const std::vector<double>& steps, int fit_from) {
    std::vector<long> counts = sim::count_cells(rule, n, boundary);
    counts.erase(counts.begin(), counts.begin() + (fit_from - 1));
    // A rule that dies leaves zero counts, which have no logarithm: its
    // pattern is a point, dimension 0.
    if (std::any_of(counts.begin(), counts.end(), [](long c) { return c <= 0; })) return 0.0;
    return sim::fit_log_log(steps, std::vector<double>(counts.begin(), counts.end())).slope;
}

}  // namespace

void render_cell1d_survey(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"n", "rows per CA for the slope (the book's count_cells n)"},
                     {"fit_from", "first step of the fitted range (the book's Fig 7.7 fits from 1)"},
                     {"tolerance", "a slope between 1 + tolerance and 2 - tolerance counts as non-integer"},
                     {"gallery_steps", "steps drawn for each gallery panel"},
                     {"gallery_columns", "gallery panels per row"}});
    auto keys = field_spec_keys();
    keys.push_back({"zero_colour", "colour of the zero-boundary slopes"});
    keys.push_back({"wrap_colour", "colour of the wrapped slopes"});
    Settings style("style", d.style, with_plot_style_keys(keys));
    int n = 0, fit_from = 1, gallery_steps = 0, columns = 0;
    double tolerance = 0;
    try {
        n = params.count("n", 500);
        sim::require_integer("n", n, 3, 100000);
        fit_from = params.count("fit_from", 10);
        sim::require_integer("fit_from", fit_from, 1, n - 2);
        tolerance = params.number("tolerance", 0.1);
        sim::require_number("tolerance", tolerance, 0.0, 0.5);
        gallery_steps = params.count("gallery_steps", 63);
        sim::require_integer("gallery_steps", gallery_steps, 1, 10000);
        columns = params.count("gallery_columns", 8);
        sim::require_integer("gallery_columns", columns, 1, 64);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const FieldSpec spec =
        read_field_spec(style, {render::colormap("Blues"), 0.0, 1.0, 0.7f, render::Sampling::nearest});
    const glm::vec4 zero_colour = style_colour(style, "zero_colour", "#526e97");
    const glm::vec4 wrap_colour = style_colour(style, "wrap_colour", "orange");
    progress.start(d.id, 256 * 2 + 1);

    std::vector<double> steps;
    for (int i = fit_from; i < n; ++i) steps.push_back(i);
    std::vector<double> rules, zero_slopes, wrap_slopes;
    nlohmann::json table = nlohmann::json::array();
    std::vector<int> fractal;
    nlohmann::json fractal_meta = nlohmann::json::array();
    // A fractal pattern in the plane has 1 < D < 2: a slope at least
    // `tolerance` from both. (Rules that turn the background on give slopes
    // just under 1 from their edges; they are not fractal.)
    auto non_integer = [&](double s) { return s > 1 + tolerance && s < 2 - tolerance; };
    for (int rule = 0; rule < 256; ++rule) {
        const double zero = slope_of(rule, n, sim::Boundary::zero, steps, fit_from);
        progress.advance();
        const double wrap = slope_of(rule, n, sim::Boundary::wrap, steps, fit_from);
        progress.advance();
        rules.push_back(rule);
        zero_slopes.push_back(zero);
        wrap_slopes.push_back(wrap);
        const bool fractal_zero = non_integer(zero), fractal_wrap = non_integer(wrap);
        table.push_back({{"rule", rule},
                         {"slope_zero", zero},
                         {"slope_wrap", wrap},
                         {"non_integer_zero", fractal_zero},
                         {"non_integer_wrap", fractal_wrap}});
        // The gallery shows rules that are non-integer with either boundary.
        if (fractal_zero || fractal_wrap) {
            fractal.push_back(rule);
            fractal_meta.push_back({{"rule", rule}, {"slope_zero", zero}, {"slope_wrap", wrap}});
        }
    }

    render::Axes survey;
    survey.x_label = "Rule";
    survey.y_label = "Slope of log cells vs log steps";
    survey.x_range = std::pair{-4.0, 259.0};
    survey.legend = render::Legend::upper_right;
    survey.series = {
        line_series({-4, 259}, {std::log2(3.0), std::log2(3.0)}, "log2 3 = 1.585", glm::vec4(0.6f, 0.6f, 0.6f, 1), 1.0f,
                    true),
        dot_series(rules, zero_slopes, "zero boundary", zero_colour, 5.0f),
        dot_series(rules, wrap_slopes, "wrapped", wrap_colour, 3.0f),
    };

    std::vector<FieldPanel> gallery;
    std::vector<std::uint8_t> gallery_cells;  // every gallery CA's cells, one after another
    for (std::size_t i = 0; i < fractal.size(); ++i) {
        sim::Cell1DParams p;
        p.rule = fractal[i];
        p.rows = gallery_steps + 1;
        p.boundary = sim::Boundary::wrap;
        sim::Cell1D ca(p);
        for (int s = 0; s < gallery_steps; ++s) ca.step();
        gallery_cells.insert(gallery_cells.end(), ca.cells().cells().begin(), ca.cells().cells().end());
        gallery.push_back({"rule " + std::to_string(p.rule) + ", D = " + format_fixed(wrap_slopes[fractal[i]], 2),
                           {field_layer(ca.cells(), spec)}});
    }
    progress.advance();
    // The survey's plotted slopes: every rule's zero-boundary slope, then its wrapped one.
    std::vector<double> slopes(zero_slopes);
    slopes.insert(slopes.end(), wrap_slopes.begin(), wrap_slopes.end());

    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    const float plot_height = std::round(height * 0.45f);
    draw_plot_row(canvas, {0, 0, float(width), plot_height}, {survey}, read_plot_style(style, options.scale));
    if (!gallery.empty())
        draw_field_panels(canvas, {0, plot_height, float(width), float(height) - plot_height}, gallery, columns,
                          options.scale);

    write_figure(d, options, canvas.read(),
                 {{"params", params.used()},
                  {"style", style.used()},
                  {"rules", table},
                  {"non_integer", fractal_meta},
                  {"state_sha256", state_hash(slopes)},
                  {"gallery",
                   {{"steps", gallery_steps},
                    {"boundary", "wrap"},
                    {"rules", fractal},
                    {"state_sha256", render::sha256_hex(gallery_cells.data(), gallery_cells.size())}}}});
    progress.finish();
}

}  // namespace figures
