// On cells against time on log-log axes, one panel per rule (Think
// Complexity 2e, Fig 7.7): the box-counting estimate of a 1-D CA's dimension.
#include <cmath>

#include "scenes/field_stats.hpp"
#include "scenes/model_check.hpp"
#include "scenes/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/figure_caption.hpp"
#include "sim/cell1d.hpp"
#include "sim/check.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

const std::vector<Key> param_keys = {
    {"rules", "Wolfram rule numbers, one panel each"},
    {"n", "rows of each CA; counts are taken at i = 1 .. n-1 (the book's count_cells)"},
    {"boundary", "\"zero\" or \"wrap\""},
};

std::vector<Key> style_keys() {
    return with_plot_style_keys({{"d2_colour", "colour of the y = i^2 line"},
                                 {"series_colour", "colour of the rule's counts"},
                                 {"d1_colour", "colour of the y = i line"},
                                 {"line_width", "line width in pixels at scale 1"}});
}

std::vector<int> read_rules(Settings& s) {
    std::vector<int> rules;
    for (long long r : s.integers("rules", {20, 50, 18})) {
        check_model(s, [&] { sim::require_integer("rules", r, 0, 255); });
        rules.push_back(static_cast<int>(r));
    }
    if (rules.empty()) s.refuse("rules", "one rule at least");
    return rules;
}

sim::Boundary read_boundary(Settings& s) {
    const std::string text = s.text("boundary", "zero");
    sim::Boundary boundary = sim::Boundary::zero;
    check_model(s, [&] { boundary = sim::parse_boundary(text); });
    return boundary;
}

class CellCountsScene : public SceneBase {
public:
    CellCountsScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_keys, style_keys()),
          rules_(read_rules(params_)),
          n_(params_.count_in("n", 500, 3, 100000)),
          boundary_(read_boundary(params_)),
          d2_(style_colour(style_, "d2_colour", "#526e97")),
          series_(style_colour(style_, "series_colour", "#619aca")),
          d1_(style_colour(style_, "d1_colour", "#96c5e1")),
          line_width_(static_cast<float>(style_.number_in("line_width", 2.0, 0.1, 50.0))),
          plot_(read_plot_style(style_, options.scale)) {}

    // count_cells' automaton: n rows of 2n + 1 cells, one rule at a time.
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("rows of cells of a byte", n_, 2.0 * n_ + 1.0, 1, 1)};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(rules_.size()));
        std::vector<render::Axes> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        std::vector<double> steps, squares;
        for (int i = 1; i < n_; ++i) {
            steps.push_back(i);
            squares.push_back(double(i) * i);
        }
        for (int rule : rules_) {
            const std::vector<long> counts = sim::count_cells(rule, n_, boundary_);
            const std::vector<double> cells(counts.begin(), counts.end());
            const sim::LineFit fit = sim::fit_log_log(steps, cells);
            panels.push_back(rule_plot(rule, steps, squares, cells, panels.empty()));
            panel_meta.push_back({{"rule", rule},
                                  {"steps", n_ - 1},
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
        axes.series = {line_series(steps, squares, "d=2", d2_, line_width_, true),
                       line_series(steps, cells, "rule=" + std::to_string(rule), series_, line_width_, false),
                       line_series(steps, steps, "d=1", d1_, line_width_, true)};
        return axes;
    }

    const std::vector<int> rules_;
    const int n_;
    const sim::Boundary boundary_;
    const glm::vec4 d2_, series_, d1_;
    const float line_width_;
    const render::PlotStyle plot_;
};

std::unique_ptr<Scene> read_cell_counts(const Description& d, const SceneOptions& options) {
    return std::make_unique<CellCountsScene>(d, options);
}

}  // namespace

SceneInfo cell_counts_scene() {
    // Its key numbers (app/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
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
