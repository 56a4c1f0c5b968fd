// Percolation's cluster against the array (Think Complexity 2e, Fig 7.9).
// tc7-9: cells in the percolating cluster against array size, at q near
// critical, log-log, with the lines of dimension 2 and 1.
#include <stdexcept>

#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/percolation_common.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

constexpr long long most_size = 4096;  // 16 MB a model, and sum n^2 runs of test_perc

struct Params {
    double q = 0.59;
    std::vector<long long> sizes{10, 100};
    int first = 10, last = 100;  // the sizes, checked
};

const Schema<Params> param_schema =
    Schema<Params>()
        .number("q", &Params::q, "probability that a cell is porous", 0.0, 1.0)
        .key({"sizes", "[first, last]: every array size in between is tried once", "a list of integers",
              "[first, last] with 2 <= first <= last <= " + std::to_string(most_size), nlohmann::json({10, 100})},
             [](Settings& s, const std::string& key, Params& p) {
                 p.sizes = s.integers(key, p.sizes);
                 if (p.sizes.size() != 2 || p.sizes[0] < 2 || p.sizes[1] < p.sizes[0] || p.sizes[1] > most_size)
                     s.refuse(key, "[first, last] with 2 <= first <= last <= " + std::to_string(most_size));
                 p.first = static_cast<int>(p.sizes[0]);
                 p.last = static_cast<int>(p.sizes[1]);
             });

struct Style {
    Colour d2 = colour("#526e97"), dots = colour("#4f80b8"), d1 = colour("#7ab2d7");
    double line_width = 3.0, marker_size = 5.0;
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"d2_colour", "colour of the size^2 line", "a colour"}, &Style::d2, read_colour)
        .field({"dots_colour", "colour of the cluster sizes", "a colour"}, &Style::dots, read_colour)
        .field({"d1_colour", "colour of the size line", "a colour"}, &Style::d1, read_colour)
        .number("line_width", &Style::line_width, "reference line width, pixels at scale 1", 0.1, 20.0)
        .number("marker_size", &Style::marker_size, "dot diameter, pixels at scale 1", 0.5, 50.0)
        .part(plot_settings_schema(), &Style::plot);

// What one run per size measured: the sizes that percolated, their squares
// and their cluster cells.
struct Clusters {
    std::vector<double> kept, squares, filled;
};

class PercolationScalingScene : public SceneBase {
public:
    PercolationScalingScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          plot_style_(plot_style(s_.plot, options.scale)) {}

    // One run at a time, the largest last: its cells, a byte each, and as much again for
    // its wet fronts (the cells wetted in one step, a small share of the
    // grid: tc7-phase at n = 4096 peaked 17 MiB over the program).
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("a run's cells and wet fronts", p_.last, p_.last, 2, 1)};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, p_.last - p_.first + 1);
        const Clusters c = measure(progress);
        if (c.kept.size() < 2) throw std::runtime_error(d_.id + ": fewer than two runs percolated; no slope to fit");
        const sim::LineFit fit = sim::fit_log_log(c.kept, c.filled);
        // The plotted numbers: the sizes that percolated, then their cluster cells.
        std::vector<double> plotted(c.kept);
        plotted.insert(plotted.end(), c.filled.begin(), c.filled.end());
        nlohmann::json meta = {
            {"params", params_.used()},
            {"style", style_.used()},
            {"runs", p_.last - p_.first + 1},
            {"percolating_runs", c.kept.size()},
            {"sizes", c.kept},
            {"cluster_cells", c.filled},
            {"slope", fit.slope},
            {"intercept", fit.intercept},
            {"r", fit.r},
            {"state_sha256", state_hash(plotted)},
        };
        out.figure(plot_figure({axes(c)}, d_, options_, plot_style_),
                   meta);
        progress.finish();
    }

private:
    // The book's test_perc once per size, all from one stream in order of size.
    Clusters measure(Progress& progress) const {
        sim::Random rng(d_.seed);
        Clusters c;
        for (int size = p_.first; size <= p_.last; ++size) {
            long wet = 0;
            if (test_perc(size, p_.q, rng, &wet).percolates) {
                c.kept.push_back(size);
                c.squares.push_back(double(size) * size);
                c.filled.push_back(double(wet - size));  // the book: num_wet minus the initial top row
            }
            progress.advance();
        }
        return c;
    }

    // Log-log, on the book's ranges: size^2, the cluster cells, size.
    render::Axes axes(const Clusters& c) const {
        render::Axes axes;
        axes.x_scale = axes.y_scale = render::Scale::log;
        axes.x_range = std::pair{9.0, 110.0};
        axes.y_range = std::pair{9.0, 20000.0};
        axes.x_label = "Array Size";
        axes.y_label = "Cell Count";
        axes.legend = render::Legend::upper_left;
        axes.series = {line_series(c.kept, c.squares, "d=2", s_.d2.rgba, float(s_.line_width), false),
                       dot_series(c.kept, c.filled, "filled", s_.dots.rgba, float(s_.marker_size)),
                       line_series(c.kept, c.kept, "d=1", s_.d1.rgba, float(s_.line_width), false)};
        return axes;
    }

    const Params p_;
    const Style s_;
    const render::PlotStyle plot_style_;
};

std::unique_ptr<Scene> read_percolation_scaling(const Description& d, const SceneOptions& options) {
    return std::make_unique<PercolationScalingScene>(d, options);
}

}  // namespace

SceneInfo percolation_scaling_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"percolation_scaling",
            read_percolation_scaling,
            {},
            {
                {"/slope",
                 "slope (fractal dimension)",
                 "number",
                 "",
                 {{"", "often near 1.85 (book); 91/48 = 1.896 (incipient cluster)"}}},
                {"/sizes", "sizes fitted", "range", ""},
                {"/percolating_runs", "runs that percolate", "integer", ""},
                {"/runs", "runs", "integer", ""},
            }};
}

}  // namespace scenes
