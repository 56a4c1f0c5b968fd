// Percolation's cluster against the array (Think Complexity 2e, Fig 7.9).
// tc7-9: cells in the percolating cluster against array size, at q near
// critical, log-log, with the lines of dimension 2 and 1.
#include <stdexcept>

#include "scenes/field_stats.hpp"
#include "scenes/percolation_common.hpp"
#include "scenes/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/figure_caption.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

const std::vector<Key> param_keys = {
    {"q", "probability that a cell is porous"},
    {"sizes", "[first, last]: every array size in between is tried once"},
};

std::vector<Key> style_keys() {
    return with_plot_style_keys({{"d2_colour", "colour of the size^2 line"},
                                 {"dots_colour", "colour of the cluster sizes"},
                                 {"d1_colour", "colour of the size line"},
                                 {"line_width", "reference line width, pixels at scale 1"},
                                 {"marker_size", "dot diameter, pixels at scale 1"}});
}

constexpr long long most_size = 4096;  // 16 MB a model, and sum n^2 runs of test_perc

struct SizeRange {
    int first, last;
};

SizeRange read_sizes(Settings& s) {
    const auto sizes = s.integers("sizes", {10, 100});
    if (sizes.size() != 2 || sizes[0] < 2 || sizes[1] < sizes[0] || sizes[1] > most_size)
        s.refuse("sizes", "[first, last] with 2 <= first <= last <= " + std::to_string(most_size));
    return {static_cast<int>(sizes[0]), static_cast<int>(sizes[1])};
}

// What one run per size measured: the sizes that percolated, their squares
// and their cluster cells.
struct Clusters {
    std::vector<double> kept, squares, filled;
};

class PercolationScalingScene : public SceneBase {
public:
    PercolationScalingScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_keys, style_keys()),
          q_(params_.number_in("q", 0.59, 0.0, 1.0)),
          sizes_(read_sizes(params_)),
          d2_colour_(style_colour(style_, "d2_colour", "#526e97")),
          dots_colour_(style_colour(style_, "dots_colour", "#4f80b8")),
          d1_colour_(style_colour(style_, "d1_colour", "#7ab2d7")),
          line_width_(static_cast<float>(style_.number_in("line_width", 3.0, 0.1, 20.0))),
          marker_size_(static_cast<float>(style_.number_in("marker_size", 5.0, 0.5, 50.0))),
          plot_style_(read_plot_style(style_, options.scale)) {}

    // One run at a time, the largest last: its cells, a byte each, and as much again for
    // its wet fronts (the cells wetted in one step, a small share of the
    // grid: tc7-phase at n = 4096 peaked 17 MiB over the program).
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("a run's cells and wet fronts", sizes_.last, sizes_.last, 2, 1)};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, sizes_.last - sizes_.first + 1);
        const Clusters c = measure(progress);
        if (c.kept.size() < 2) throw std::runtime_error(d_.id + ": fewer than two runs percolated; no slope to fit");
        const sim::LineFit fit = sim::fit_log_log(c.kept, c.filled);
        // The plotted numbers: the sizes that percolated, then their cluster cells.
        std::vector<double> plotted(c.kept);
        plotted.insert(plotted.end(), c.filled.begin(), c.filled.end());
        nlohmann::json meta = {
            {"params", params_.used()},
            {"style", style_.used()},
            {"runs", sizes_.last - sizes_.first + 1},
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
        for (int size = sizes_.first; size <= sizes_.last; ++size) {
            long wet = 0;
            if (test_perc(size, q_, rng, &wet).percolates) {
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
        axes.series = {line_series(c.kept, c.squares, "d=2", d2_colour_, line_width_, false),
                       dot_series(c.kept, c.filled, "filled", dots_colour_, marker_size_),
                       line_series(c.kept, c.kept, "d=1", d1_colour_, line_width_, false)};
        return axes;
    }

    const double q_;
    const SizeRange sizes_;
    const glm::vec4 d2_colour_, dots_colour_, d1_colour_;
    const float line_width_, marker_size_;
    const render::PlotStyle plot_style_;
};

std::unique_ptr<Scene> read_percolation_scaling(const Description& d, const SceneOptions& options) {
    return std::make_unique<PercolationScalingScene>(d, options);
}

}  // namespace

SceneInfo percolation_scaling_scene() {
    // Its key numbers (app/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
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
