// The forest-fire model (Bak, Chen & Tang 1990; Think Complexity 2e,
// exercise 7.2): the forest at three steps, the tree and fire counts over
// time, and the forest's box-counting dimension at the last step.
#include "sim/forest_fire.hpp"

#include <cmath>
#include <numeric>

#include "base/digest.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

using P = sim::ForestFireParams;
const Schema<P> param_schema =
    Schema<P>()
        .count("n", &P::n, "grid size (a torus)")
        .number("p", &P::p, "probability that an empty cell grows a tree")
        .number("f", &P::f, "probability that a tree ignites by itself")
        .key({"initial_density", "probability that a cell starts as a tree; absent: p", "a number"},
             [](Settings& s, const std::string& key, P& v) { v.initial_density = s.number(key, v.p); })
        .check(validated<P>());

struct Style {
    FieldSpec field{render::listed_colormap("forest", {{1, 1, 1}, {0, 0.5f, 0}, {1, 0.65f, 0}}), 0.0, 2.0, 1.0f,
                    render::Sampling::nearest};
    Colour trees = colour("green"), fires = colour("orange");
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .part(field_spec_schema(), &Style::field)
        .field({"trees_colour", "colour of the tree count", "a colour"}, &Style::trees, read_colour)
        .field({"fires_colour", "colour of the fire count", "a colour"}, &Style::fires, read_colour)
        .part(plot_settings_schema(), &Style::plot);

// States 0, 1, 5 as colour indices 0, 1, 2 of a three-colour listed map.
sim::Grid<std::uint8_t> colour_index(const sim::Grid<std::uint8_t>& cells) {
    sim::Grid<std::uint8_t> index(cells.rows(), cells.cols());
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto c = cells.data()[i];
        index.data()[i] = c == sim::ForestFire::tree ? 1 : c == sim::ForestFire::fire ? 2 : 0;
    }
    return index;
}

// What the run leaves for the figure: the panels and the counts at every step.
struct ForestHistory {
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    std::vector<double> steps, trees, fires;

    void count(const sim::ForestFire& model) {
        steps.push_back(model.steps());
        trees.push_back(double(model.trees()));
        fires.push_back(double(model.fires()));
    }
};

// The forest at its last step: boxes of side 1, 2, 4, ... holding a tree,
// and the book's solution's measure, trees in a centred box of side i.
struct ForestDimension {
    sim::BoxCount boxes;
    sim::MassScaling mass;
};

nlohmann::json panel_metadata(const sim::ForestFire& model, int step) {
    return {{"step", step},
            {"statistics", {{"trees", model.trees()}, {"fires", model.fires()}, {"empty", model.empties()}}},
            {"state_sha256", base::sha256_hex(model.cells().data(), model.cells().size())}};
}

// Tree and fire counts over time on a log axis.
render::Axes counts_plot(const ForestHistory& history, glm::vec4 trees_colour, glm::vec4 fires_colour) {
    render::Axes counts;
    counts.x_label = "Time Steps";
    counts.y_label = "Cells";
    counts.y_scale = render::Scale::log;
    counts.legend = render::Legend::lower_right;
    // Fires can be 0: a log axis skips those points, which is honest.
    counts.series = {line_series(history.steps, history.trees, "trees", trees_colour, 2.0f, false),
                     line_series(history.steps, history.fires, "fires", fires_colour, 1.5f, false)};
    return counts;
}

// Box counts and centred-box masses against box size, log-log.
render::Axes dimension_plot(const ForestDimension& dim, double cells, glm::vec4 trees_colour) {
    render::Axes dimension;
    dimension.x_scale = dimension.y_scale = render::Scale::log;
    dimension.x_label = "Box Size";
    dimension.y_label = "Count";
    dimension.legend = render::Legend::upper_left;
    // Headroom above the data for the legend.
    dimension.y_range = std::pair{0.5, 30.0 * cells};
    const sim::BoxCount& boxes = dim.boxes;
    const sim::MassScaling& mass = dim.mass;
    std::vector<double> sizes(boxes.box_sizes.begin(), boxes.box_sizes.end());
    std::vector<double> occupied(boxes.occupied.begin(), boxes.occupied.end());
    std::vector<double> mass_sizes(mass.sizes.begin(), mass.sizes.end());
    std::vector<double> mass_counts(mass.mass.begin(), mass.mass.end());
    dimension.series = {
        line_series(sizes, occupied, "boxes with a tree, D = " + format_fixed(boxes.dimension, 2), trees_colour, 2.0f,
                    false),
        dot_series(sizes, occupied, "", trees_colour, 6.0f),
        line_series(mass_sizes, mass_counts, "trees in centred box, slope " + format_fixed(mass.fit.slope, 2),
                    glm::vec4(0.32f, 0.43f, 0.59f, 1.0f), 2.0f, true),
    };
    return dimension;
}

class ForestFireScene : public SceneBase {
public:
    ForestFireScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          plot_(plot_style(s_.plot, options.scale)) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "one step at least");
        require_drawable(params_, "n", "the forest", p_.n, p_.n);
    }

    // The cells, their next step, the colour index and a copy per panel.
    std::vector<MemoryNeed> memory() const override {
        // The model's grids, each panel's values as doubles and its texture.
        return {grid_need("grids of bytes", p_.n, p_.n, 1, 3.0 + double(d_.panels.size())),
                grid_need("field panels", p_.n, p_.n, 8 + field_layer_bytes_per_cell, double(d_.panels.size()))};
    }

    void render(Output& out) const override {
        StepRunner run(d_, options_, out);
        sim::ForestFire model(p_, d_.seed);
        const ForestHistory history = run_forest(run, model);
        if (run.film_only()) return run.finish_film();  // a film segment's run: no figure
        const ForestDimension dim{sim::box_count(model.cells(), sim::ForestFire::tree),
                                  sim::central_box_mass(model.cells(), sim::ForestFire::tree)};
        const render::Axes counts = counts_plot(history, s_.trees.rgba, s_.fires.rgba);
        const render::Axes dimension = dimension_plot(dim, double(model.cells().size()), s_.trees.rgba);
        run.write_figure(draw_figure(history, counts, dimension), metadata(history, dim));
    }

private:
    // Steps the forest to the last step, keeping its panels and counts.
    ForestHistory run_forest(StepRunner& run, sim::ForestFire& model) const {
        ForestHistory history;
        auto panel = [&](const std::string& pattern, int step) {
            return FieldPanel{format_step(pattern, step), {field_layer(colour_index(model.cells()), s_.field)}};
        };
        run.run({
            .check = {},
            .panel =
                [&](int step) {
                    history.panels.push_back(panel(d_.panel_title, step));
                    history.panel_meta.push_back(panel_metadata(model, step));
                },
            .frame = [&](int step) -> FrameDrawing { return run.field_frame({panel(d_.animation->title, step)}); },
            .advance =
                [&] {
                    history.count(model);
                    model.step();
                    return true;
                },
        });
        history.count(model);
        return history;
    }

    // The forest's panels above, the counts and the dimension plots below.
    FigureDrawing draw_figure(const ForestHistory& history, const render::Axes& counts,
                              const render::Axes& dimension) const {
        require_text_fits(
            d_, options_,
            [&](const render::Rect& area) {
                const float top = std::round(area.h * 0.52f);
                render::PageText page = field_panels_text({area.x, area.y, area.w, top}, history.panels,
                                                          static_cast<int>(history.panels.size()), options_.scale);
                page.add(plot_row_text({area.x, area.y + top, area.w, area.h - top}, {counts, dimension}, plot_));
                return page;
            },
            plot_remedy);
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        return {width, height, false, [this, &history, &counts, &dimension](render::Surface& surface) {
                    const float w = float(surface.width()), h = float(surface.height());
                    surface.background({1, 1, 1, 1});
                    const float top = std::round(h * 0.52f);
                    draw_field_panels(surface, {0, 0, w, top}, history.panels,
                                      static_cast<int>(history.panels.size()), options_.scale);
                    draw_plot_row(surface, {0, top, w, h - top}, {counts, dimension}, plot_);
                }};
    }

    nlohmann::json metadata(const ForestHistory& history, const ForestDimension& dim) const {
        const std::vector<double>& trees = history.trees;
        const std::size_t half = trees.size() / 2;
        const double steady_trees =
            std::accumulate(trees.begin() + half, trees.end(), 0.0) / double(trees.size() - half);
        return {
            {"params", params_.used()},
            {"style", style_.used()},
            {"panels", history.panel_meta},
            {"trees_over_time", trees},
            {"fires_over_time", history.fires},
            {"steady_state_trees", steady_trees},
            {"box_counting",
             {{"box_sizes", dim.boxes.box_sizes},
              {"occupied", dim.boxes.occupied},
              {"dimension", dim.boxes.dimension},
              {"r", dim.boxes.fit.r}}},
            {"central_box_mass", {{"sizes", dim.mass.sizes}, {"mass", dim.mass.mass}, {"slope", dim.mass.fit.slope}}},
        };
    }

    const sim::ForestFireParams p_;
    const Style s_;
    const render::PlotStyle plot_;
};

std::unique_ptr<Scene> read_forest_fire(const Description& d, const SceneOptions& options) {
    return std::make_unique<ForestFireScene>(d, options);
}

}  // namespace

SceneInfo forest_fire_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"forest_fire",
            read_forest_fire,
            {"colormap"},
            {
                {"/central_box_mass/slope",
                 "dimension (trees in a central box)",
                 "number",
                 "",
                 {{"", "close to 2 (the book's solution)"}}},
                {"/box_counting/dimension",
                 "dimension (box counting)",
                 "number",
                 "",
                 {{"", "close to 2 (the book's solution)"}}},
                {"/steady_state_trees", "steady-state trees", "number", ""},
            }};
}

}  // namespace scenes
