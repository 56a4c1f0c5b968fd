// Think Complexity 2e, exercise 7.1: which elementary CAs are fractal? The
// cell-count slope (the box-counting dimension of section 7.5) of all 256
// rules, without and with wrapping, and a gallery of those whose slope is
// not an integer.
#include <algorithm>
#include <thread>
#include <cmath>

#include "base/digest.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"
#include "sim/cell1d.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

struct Params {
    int n = 500, fit_from = 10;
    double tolerance = 0.1;
    int gallery_steps = 63, columns = 8;
};

const Schema<Params> param_schema =
    Schema<Params>()
        .count("n", &Params::n, "rows per CA for the slope (the book's count_cells n)", 3, 100000)
        .key({"fit_from", "first step of the fitted range (the book's Fig 7.7 fits from 1)", "an integer",
              "an integer from 1 to n - 2", 10},
             [](Settings& s, const std::string& key, Params& p) {
                 p.fit_from = s.count_in(key, p.fit_from, 1, p.n - 2);
             })
        .number("tolerance", &Params::tolerance,
                "a slope between 1 + tolerance and 2 - tolerance counts as non-integer", 0.0, 0.5)
        .count("gallery_steps", &Params::gallery_steps, "steps drawn for each gallery panel", 1, 10000)
        .count("gallery_columns", &Params::columns, "gallery panels per row", 1, 64);

struct Style {
    FieldSpec field{render::colormap("Blues"), 0.0, 1.0, 0.7f, render::Sampling::nearest};
    Colour zero = colour("#526e97"), wrap = colour("orange");
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .part(field_spec_schema(), &Style::field)
        .field({"zero_colour", "colour of the zero-boundary slopes", "a colour"}, &Style::zero, read_colour)
        .field({"wrap_colour", "colour of the wrapped slopes", "a colour"}, &Style::wrap, read_colour)
        .part(plot_settings_schema(), &Style::plot);

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

// Every rule's slopes, and which of them are non-integer.
struct Survey {
    std::vector<double> rules, zero_slopes, wrap_slopes;
    nlohmann::json table = nlohmann::json::array();
    std::vector<int> fractal;  // the gallery's rules
    nlohmann::json fractal_meta = nlohmann::json::array();
};

// The gallery: each non-integer rule's wrapped automaton, and all their cells one after another.
struct Gallery {
    std::vector<FieldPanel> panels;
    std::vector<std::uint8_t> cells;
};

// Both slopes of every rule against the rule number, with log2 3 (Sierpinski's triangle) for reference.
render::Axes survey_plot(const Survey& survey, glm::vec4 zero_colour, glm::vec4 wrap_colour) {
    render::Axes plot;
    plot.x_label = "Rule";
    plot.y_label = "Slope of log cells vs log steps";
    plot.x_range = std::pair{-4.0, 259.0};
    plot.legend = render::Legend::upper_right;
    plot.series = {
        line_series({-4, 259}, {std::log2(3.0), std::log2(3.0)}, "log2 3 = 1.585", glm::vec4(0.6f, 0.6f, 0.6f, 1), 1.0f,
                    true),
        dot_series(survey.rules, survey.zero_slopes, "zero boundary", zero_colour, 5.0f),
        dot_series(survey.rules, survey.wrap_slopes, "wrapped", wrap_colour, 3.0f),
    };
    return plot;
}

// Work items: one a rule, both of its slopes.
class Cell1DSurveyScene : public SceneBase, public WorkItems {
public:
    Cell1DSurveyScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          plot_(plot_style(s_.plot, options.scale)) {
        // A gallery automaton: gallery_steps + 1 rows of the default width, 2 * rows + 1.
        const double rows = p_.gallery_steps + 1.0;
        require_drawable(params_, "gallery_steps", "each gallery panel", rows, 2.0 * rows + 1.0);
    }

    // count_cells' automaton: n rows of 2n + 1 cells, one rule at a time on each thread.
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("rows of cells of a byte, one automaton a thread", p_.n, 2.0 * p_.n + 1.0, 1,
                          double(options_.threads))};
    }

    const WorkItems* work() const override { return this; }
    int item_count() const override { return 256; }
    std::string item_name(int item) const override { return "rule " + std::to_string(item); }
    double item_bytes() const override { return 256; }
    nlohmann::json run_item(int rule) const override {
        std::vector<double> steps;
        for (int i = p_.fit_from; i < p_.n; ++i) steps.push_back(i);
        return {{"slope_zero", slope_of(rule, p_.n, sim::Boundary::zero, steps, p_.fit_from)},
                {"slope_wrap", slope_of(rule, p_.n, sim::Boundary::wrap, steps, p_.fit_from)}};
    }

    // Two slopes of a log-log fit: finite numbers.
    void check_result(int, const nlohmann::json& r) const override {
        namespace rc = result_check;
        const double huge = std::numeric_limits<double>::max();
        rc::number_in(rc::member(r, "slope_zero"), "slope_zero", -huge, huge);
        rc::number_in(rc::member(r, "slope_wrap"), "slope_wrap", -huge, huge);
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, item_count() + 1);
        const Survey survey = survey_rules(out.results(*this));
        const render::Axes plot = survey_plot(survey, s_.zero.rgba, s_.wrap.rgba);
        const Gallery gallery = gallery_of(survey);
        progress.advance();
        // The survey's plotted slopes: every rule's zero-boundary slope, then its wrapped one.
        std::vector<double> slopes(survey.zero_slopes);
        slopes.insert(slopes.end(), survey.wrap_slopes.begin(), survey.wrap_slopes.end());
        out.figure(draw_figure(plot, gallery),
                   {{"params", params_.used()},
                    {"style", style_.used()},
                    {"rules", survey.table},
                    {"non_integer", survey.fractal_meta},
                    {"state_sha256", state_hash(slopes)},
                    {"gallery",
                     {{"steps", p_.gallery_steps},
                      {"boundary", "wrap"},
                      {"rules", survey.fractal},
                      {"state_sha256", base::sha256_hex(gallery.cells.data(), gallery.cells.size())}}}});
        progress.finish();
    }

private:
    // The 256 rules' slopes, from their items' results.
    Survey survey_rules(const std::vector<nlohmann::json>& results) const {
        Survey survey;
        // A fractal pattern in the plane has 1 < D < 2: a slope at least
        // `tolerance` from both. (Rules that turn the background on give slopes
        // just under 1 from their edges; they are not fractal.)
        auto non_integer = [&](double s) { return s > 1 + p_.tolerance && s < 2 - p_.tolerance; };
        for (int rule = 0; rule < 256; ++rule) {
            const double zero = results[rule].at("slope_zero").get<double>();
            const double wrap = results[rule].at("slope_wrap").get<double>();
            survey.rules.push_back(rule);
            survey.zero_slopes.push_back(zero);
            survey.wrap_slopes.push_back(wrap);
            const bool fractal_zero = non_integer(zero), fractal_wrap = non_integer(wrap);
            survey.table.push_back({{"rule", rule},
                                    {"slope_zero", zero},
                                    {"slope_wrap", wrap},
                                    {"non_integer_zero", fractal_zero},
                                    {"non_integer_wrap", fractal_wrap}});
            // The gallery shows rules that are non-integer with either boundary.
            if (fractal_zero || fractal_wrap) {
                survey.fractal.push_back(rule);
                survey.fractal_meta.push_back({{"rule", rule}, {"slope_zero", zero}, {"slope_wrap", wrap}});
            }
        }
        return survey;
    }

    // Each non-integer rule run wrapped for gallery_steps, titled with its wrapped slope.
    Gallery gallery_of(const Survey& survey) const {
        Gallery gallery;
        for (std::size_t i = 0; i < survey.fractal.size(); ++i) {
            sim::Cell1DParams p;
            p.rule = survey.fractal[i];
            p.rows = p_.gallery_steps + 1;
            p.boundary = sim::Boundary::wrap;
            sim::Cell1D ca(p);
            for (int s = 0; s < p_.gallery_steps; ++s) ca.step();
            gallery.cells.insert(gallery.cells.end(), ca.cells().cells().begin(), ca.cells().cells().end());
            gallery.panels.push_back(
                {"rule " + std::to_string(p.rule) + ", D = " + format_fixed(survey.wrap_slopes[survey.fractal[i]], 2),
                 {field_layer(ca.cells(), s_.field)}});
        }
        return gallery;
    }

    // The survey's plot above, the gallery below.
    FigureDrawing draw_figure(const render::Axes& plot, const Gallery& gallery) const {
        require_text_fits(
            d_, options_,
            [&](const render::Rect& area) {
                const float plot_height = std::round(area.h * 0.45f);
                render::PageText page = plot_row_text({area.x, area.y, area.w, plot_height}, {plot}, plot_);
                if (!gallery.panels.empty())
                    page.add(field_panels_text({area.x, area.y + plot_height, area.w, area.h - plot_height},
                                               gallery.panels, p_.columns, options_.scale));
                return page;
            },
            plot_remedy);
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        return {width, height, false, [this, &plot, &gallery](render::Surface& surface) {
                    const float w = float(surface.width()), h = float(surface.height());
                    surface.background({1, 1, 1, 1});
                    const float plot_height = std::round(h * 0.45f);
                    draw_plot_row(surface, {0, 0, w, plot_height}, {plot}, plot_);
                    if (!gallery.panels.empty())
                        draw_field_panels(surface, {0, plot_height, w, h - plot_height}, gallery.panels, p_.columns,
                                          options_.scale);
                }};
    }

    const Params p_;
    const Style s_;
    const render::PlotStyle plot_;
};

std::unique_ptr<Scene> read_cell1d_survey(const Description& d, const SceneOptions& options) {
    return std::make_unique<Cell1DSurveyScene>(d, options);
}

}  // namespace

SceneInfo cell1d_survey_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {
        "cell1d_survey",
        read_cell1d_survey,
        {"colormap"},
        {
            {"/non_integer", "rules with non-integer slope", "count", "of 256"},
            {"/rules/*/slope_zero",
             "slope, rule {rule}",
             "number",
             "",
             {{"", "1.57 (book, Fig 7.7); log2 3 = 1.585"}},
             "rule=18"},
            {"/rules/*/slope_wrap", "slope, rule {rule} wrapped", "number", "", {{"", "log2 3 = 1.585"}}, "rule=18"},
        }};
}

}  // namespace scenes
