// The forest-fire model (Bak, Chen & Tang 1990; Think Complexity 2e,
// exercise 7.2): the forest at three steps, the tree and fire counts over
// time, and the forest's box-counting dimension at the last step.
#include <numeric>

#include "figures/field_spec.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "figures/step_runner.hpp"
#include "render/digest.hpp"
#include "sim/forest_fire.hpp"
#include "sim/fractal.hpp"

namespace figures {
namespace {

// States 0, 1, 5 as colour indices 0, 1, 2 of a three-colour listed map.
sim::Grid<std::uint8_t> colour_index(const sim::Grid<std::uint8_t>& cells) {
    sim::Grid<std::uint8_t> index(cells.rows(), cells.cols());
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto c = cells.data()[i];
        index.data()[i] = c == sim::ForestFire::tree ? 1 : c == sim::ForestFire::fire ? 2 : 0;
    }
    return index;
}

}  // namespace

void render_forest_fire(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"n", "grid size (a torus)"},
                     {"p", "probability that an empty cell grows a tree"},
                     {"f", "probability that a tree ignites by itself"},
                     {"initial_density", "probability that a cell starts as a tree"}});
    auto style_keys = field_spec_keys();
    style_keys.push_back({"trees_colour", "colour of the tree count"});
    style_keys.push_back({"fires_colour", "colour of the fire count"});
    Settings style("style", d.style, with_plot_style_keys(style_keys));
    sim::ForestFireParams p;
    try {
        p.n = params.count("n", p.n);
        p.p = params.number("p", p.p);
        p.f = params.number("f", p.f);
        p.initial_density = params.number("initial_density", p.p);
        p.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    FieldSpec defaults{render::listed_colormap("forest", {{1, 1, 1}, {0, 0.5f, 0}, {1, 0.65f, 0}}), 0.0, 2.0, 1.0f,
                       render::Sampling::nearest};
    const FieldSpec spec = read_field_spec(style, defaults);
    const glm::vec4 trees_colour = style_colour(style, "trees_colour", "green");
    const glm::vec4 fires_colour = style_colour(style, "fires_colour", "orange");
    if (d.panels.empty()) throw UsageError(d.id + ": figure.panels is empty");

    // The cells, their next step, the colour index and a copy per panel.
    require_memory(d, options, {grid_need("grids of bytes", p.n, p.n, 1, 3.0 + double(d.panels.size()))});
    StepRunner run(d, options, progress);
    sim::ForestFire model(p, d.seed);
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    std::vector<double> steps, trees, fires;
    auto panel = [&](const std::string& pattern, int step) {
        return FieldPanel{format_step(pattern, step), {field_layer(colour_index(model.cells()), spec)}};
    };
    run.run({
        .check = {},
        .panel =
            [&](int step) {
                panels.push_back(panel(d.panel_title, step));
                panel_meta.push_back(
                    {{"step", step},
                     {"statistics", {{"trees", model.trees()}, {"fires", model.fires()}, {"empty", model.empties()}}},
                     {"state_sha256", render::sha256_hex(model.cells().data(), model.cells().size())}});
            },
        .frame =
            [&](int step) {
                return draw_field_panels(run.frame_canvas(), {panel(d.animation->title, step)}, options.scale);
            },
        .advance =
            [&] {
                steps.push_back(model.steps());
                trees.push_back(double(model.trees()));
                fires.push_back(double(model.fires()));
                model.step();
                return true;
            },
    });
    steps.push_back(model.steps());
    trees.push_back(double(model.trees()));
    fires.push_back(double(model.fires()));

    // The forest at the last step: boxes of side 1, 2, 4, ... holding a tree,
    // and the book's solution's measure, trees in a centred box of side i.
    const sim::BoxCount boxes = sim::box_count(model.cells(), sim::ForestFire::tree);
    const sim::MassScaling mass = sim::central_box_mass(model.cells(), sim::ForestFire::tree);
    const std::size_t half = trees.size() / 2;
    const double steady_trees = std::accumulate(trees.begin() + half, trees.end(), 0.0) / double(trees.size() - half);

    render::Axes counts;
    counts.x_label = "Time Steps";
    counts.y_label = "Cells";
    counts.y_scale = render::Scale::log;
    counts.legend = render::Legend::lower_right;
    // Fires can be 0: a log axis skips those points, which is honest.
    counts.series = {line_series(steps, trees, "trees", trees_colour, 2.0f, false),
                     line_series(steps, fires, "fires", fires_colour, 1.5f, false)};
    render::Axes dimension;
    dimension.x_scale = dimension.y_scale = render::Scale::log;
    dimension.x_label = "Box Size";
    dimension.y_label = "Count";
    dimension.legend = render::Legend::upper_left;
    // Headroom above the data for the legend.
    dimension.y_range = std::pair{0.5, 30.0 * double(model.cells().size())};
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

    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    const float top = std::round(height * 0.52f);
    draw_field_panels(canvas, {0, 0, float(width), top}, panels, static_cast<int>(panels.size()), options.scale);
    draw_plot_row(canvas, {0, top, float(width), float(height) - top}, {counts, dimension},
                  read_plot_style(style, options.scale));

    nlohmann::json meta = {
        {"params", params.used()},
        {"style", style.used()},
        {"panels", panel_meta},
        {"trees_over_time", trees},
        {"fires_over_time", fires},
        {"steady_state_trees", steady_trees},
        {"box_counting",
         {{"box_sizes", boxes.box_sizes},
          {"occupied", boxes.occupied},
          {"dimension", boxes.dimension},
          {"r", boxes.fit.r}}},
        {"central_box_mass", {{"sizes", mass.sizes}, {"mass", mass.mass}, {"slope", mass.fit.slope}}},
    };
    run.write_figure(canvas.read(), meta);
}

}  // namespace figures
