// On cells against time on log-log axes, one panel per rule (Think
// Complexity 2e, Fig 7.7): the box-counting estimate of a 1-D CA's dimension.
#include <cmath>

#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "sim/cell1d.hpp"
#include "sim/check.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

struct Params {
    std::vector<long long> rules{20, 50, 18};
    int n = 500;
    sim::Boundary boundary = sim::Boundary::zero;
};

const Schema<Params> param_schema =
    Schema<Params>()
        .key(
            {"rules", "Wolfram rule numbers, one panel each", "a list of integers"},
            [](Settings& s, const std::string& key, Params& p) {
                p.rules = s.integers(key, p.rules);
                for (long long r : p.rules) check_model(s, [&] { sim::require_integer("rules", r, 0, 255); });
                if (p.rules.empty()) s.refuse(key, "one rule at least");
            },
            [](const Params& d) { return nlohmann::json(d.rules); })
        .count("n", &Params::n, "rows of each CA; counts are taken at i = 1 .. n-1 (the book's count_cells)", 3, 100000)
        .choice("boundary", &Params::boundary, sim::boundary_names(), "beyond the edge: zero, or the opposite edge");

struct Style {
    Colour d2 = colour("#526e97"), series = colour("#619aca"), d1 = colour("#96c5e1");
    double line_width = 2.0;
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"d2_colour", "colour of the y = i^2 line", "a colour"}, &Style::d2, read_colour)
        .field({"series_colour", "colour of the rule's counts", "a colour"}, &Style::series, read_colour)
        .field({"d1_colour", "colour of the y = i line", "a colour"}, &Style::d1, read_colour)
        .number("line_width", &Style::line_width, "line width in pixels at scale 1", 0.1, 50.0)
        .part(plot_settings_schema(), &Style::plot);

class CellCountsScene : public SceneBase {
public:
    CellCountsScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          line_width_(static_cast<float>(s_.line_width)),
          plot_(plot_style(s_.plot, options.scale)) {}

    // count_cells' automaton: n rows of 2n + 1 cells, one rule at a time.
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("rows of cells of a byte", p_.n, 2.0 * p_.n + 1.0, 1, 1)};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(p_.rules.size()));
        std::vector<render::Axes> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        std::vector<double> steps, squares;
        for (int i = 1; i < p_.n; ++i) {
            steps.push_back(i);
            squares.push_back(double(i) * i);
        }
        for (int rule : p_.rules) {
            const std::vector<long> counts = sim::count_cells(rule, p_.n, p_.boundary);
            const std::vector<double> cells(counts.begin(), counts.end());
            const sim::LineFit fit = sim::fit_log_log(steps, cells);
            panels.push_back(rule_plot(rule, steps, squares, cells, panels.empty()));
            panel_meta.push_back({{"rule", rule},
                                  {"steps", p_.n - 1},
                                  {"statistics", {{"on_cells", counts.back()}}},
                                  {"slope", fit.slope},
                                  {"intercept", fit.intercept},
                                  {"r", fit.r},
                                  {"state_sha256", state_hash(cells)}});
            progress.advance();
        }
        out.figure(plot_figure(panels, d_, options_, plot_),
                   {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
        progress.finish();
    }

private:
    // A rule's counts between the lines of dimension 2 and 1; the first panel carries the y label.
    render::Axes rule_plot(int rule, const std::vector<double>& steps, const std::vector<double>& squares,
                           const std::vector<double>& cells, bool first) const {
        render::Axes axes;
        axes.x_scale = axes.y_scale = render::Scale::log;
        axes.x_range = std::pair{1.0, 600.0};  // the book's xlim
        axes.x_label = "Time Steps";
        if (first) axes.y_label = "Number of Cells";
        axes.legend = render::Legend::upper_left;
        axes.series = {line_series(steps, squares, "d=2", s_.d2.rgba, line_width_, true),
                       line_series(steps, cells, "rule=" + std::to_string(rule), s_.series.rgba, line_width_, false),
                       line_series(steps, steps, "d=1", s_.d1.rgba, line_width_, true)};
        return axes;
    }

    const Params p_;
    const Style s_;
    const float line_width_;
    const render::PlotStyle plot_;
};

std::unique_ptr<Scene> read_cell_counts(const Description& d, const SceneOptions& options) {
    return std::make_unique<CellCountsScene>(d, options);
}

}  // namespace

SceneInfo cell_counts_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"cell_counts",
            read_cell_counts,
            {},
            {
                {"/panels/*/slope",
                 "slope, rule {rule}",
                 "number",
                 "",
                 {{"rule=20", "1.01 (book)"},
                  {"rule=50", "1.97 (book)"},
                  {"rule=18", "1.57 (book); log2 3 = 1.585 the exact limit"}}},
            }};
}

}  // namespace scenes
