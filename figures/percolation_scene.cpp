// Percolation as the book's cellular automaton (Think Complexity 2e, Figs 7.5
// and 7.8): blocked 0, porous 1, wet 5, drawn in Blues from 0 to 5.
#include "figures/field_spec.hpp"
#include "figures/scene.hpp"
#include "figures/step_runner.hpp"
#include "render/digest.hpp"
#include "sim/percolation.hpp"
#include "sim/random.hpp"

namespace figures {
namespace {

// How a run ends: the book's test_perc stops as soon as the bottom row is wet;
// the model's own fixed point comes later. Each figure says which it shows.
enum class StopRule { bottom_or_fixed_point, fixed_point };

StopRule read_stop(Settings& s) {
    const std::string stop = s.text("stop", "bottom_or_fixed_point");
    if (stop == "bottom_or_fixed_point") return StopRule::bottom_or_fixed_point;
    if (stop == "fixed_point") return StopRule::fixed_point;
    throw UsageError("params.stop = \"" + stop +
                     "\" is not allowed: use \"bottom_or_fixed_point\" (the book's test_perc) or \"fixed_point\"");
}

// One step under the stop rule: false once the run is over.
bool step_until_stop(sim::Percolation& model, StopRule stop) {
    if (stop == StopRule::bottom_or_fixed_point && model.bottom_row_wet()) return false;
    return model.step() > 0;
}

nlohmann::json panel_metadata(const sim::Percolation& model, StopRule stop, bool stopped) {
    const auto& cells = model.cells();
    long porous = 0;
    for (auto c : cells.cells()) porous += c == sim::Percolation::porous;
    nlohmann::json meta = {
        {"step", model.steps()},
        {"n", cells.rows()},
        {"statistics", {{"wet", model.wet_count()}, {"porous_dry", porous}, {"percolates", model.bottom_row_wet()}}},
        {"state_sha256", render::sha256_hex(cells.data(), cells.size())},
    };
    if (stopped)
        meta["stopped"] =
            model.bottom_row_wet() && stop == StopRule::bottom_or_fixed_point ? "bottom row wet" : "fixed point";
    return meta;
}

const FieldSpec default_spec{render::colormap("Blues"), 0.0, 5.0, 0.6f, render::Sampling::nearest};

}  // namespace

// tc7-5: one small model, panels after the first steps, the animation to the end.
void render_percolation(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"n", "grid size"},
                     {"q", "probability that a cell is porous"},
                     {"stop", "\"bottom_or_fixed_point\" or \"fixed_point\""}});
    Settings style("style", d.style, field_spec_keys());
    sim::PercolationParams p;
    StopRule stop;
    try {
        p.n = params.count("n", p.n);
        p.q = params.number("q", p.q);
        stop = read_stop(params);
        p.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const FieldSpec spec = read_field_spec(style, default_spec);
    // The cells, their next step and a copy per panel.
    require_memory(d, options, {grid_need("grids of bytes", p.n, p.n, 1, 2.0 + double(d.panels.size()))});
    sim::Random rng(d.seed);
    sim::Percolation model(p, rng);
    bool stopped = false;

    StepRunner run(d, options, progress);
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    auto title = [&](const std::string& pattern) {
        return format_step(pattern, model.steps()) + (stopped ? " (stopped)" : "");
    };
    const int reached = run.run({
        .check = {},
        .panel =
            [&](int) {
                panels.push_back({title(d.panel_title), {field_layer(model.cells(), spec)}});
                panel_meta.push_back(panel_metadata(model, stop, stopped));
            },
        .frame =
            [&](int) {
                return draw_field_panels(run.frame_canvas(),
                                         {{title(d.animation->title), {field_layer(model.cells(), spec)}}},
                                         options.scale);
            },
        .advance =
            [&] {
                stopped = !step_until_stop(model, stop);
                return !stopped;
            },
    });
    // Panels asked for after the run stopped show its final state, titled with
    // the step it stopped at.
    for (int step : d.panels)
        if (step > reached) {
            panels.push_back({title(d.panel_title), {field_layer(model.cells(), spec)}});
            panel_meta.push_back(panel_metadata(model, stop, stopped));
        }
    nlohmann::json meta = {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}};
    run.write_field_figure(panels, meta);
}

// tc7-8: one run per size, each to its stop; the animation follows the last
// (largest) run's wetting front as it happens.
void render_percolation_sizes(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"sizes", "grid sizes, one panel each"},
                     {"q", "probability that a cell is porous"},
                     {"stop", "\"bottom_or_fixed_point\" or \"fixed_point\""}});
    Settings style("style", d.style, field_spec_keys());
    std::vector<sim::PercolationParams> runs;
    StopRule stop;
    try {
        const double q = params.number("q", 0.6);
        for (long long n : params.integers("sizes", {100, 200, 300})) {
            sim::PercolationParams p;
            p.n = static_cast<int>(std::clamp<long long>(n, -1, 1 << 20));
            p.q = q;
            p.validate();
            runs.push_back(p);
        }
        stop = read_stop(params);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (runs.empty()) throw UsageError(d.id + ": params.sizes is empty");
    const FieldSpec spec = read_field_spec(style, default_spec);

    const bool animate = d.animation && options.animates();
    std::unique_ptr<FrameSink> sink;
    const int fw = animate ? scaled_even(d.animation->width, options.scale) : 0;
    const int fh = animate ? scaled_even(d.animation->height, options.scale) : 0;
    std::unique_ptr<render::Canvas> film_canvas;
    if (animate) {
        sink = std::make_unique<FrameSink>(d, options, fw, fh);
        film_canvas = std::make_unique<render::Canvas>(fw, fh);
    }
    progress.start(d.id, static_cast<long long>(runs.size()));

    sim::Random rng(d.seed);  // the runs draw from one stream, in order
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    for (std::size_t i = 0; i < runs.size(); ++i) {
        sim::Percolation model(runs[i], rng);
        const bool film = sink && i + 1 == runs.size();
        auto film_frame = [&] {
            const auto title =
                expand(d.animation->title, {{"n", std::to_string(runs[i].n)}, {"step", std::to_string(model.steps())}});
            sink->add(draw_field_panels(*film_canvas, {{title, {field_layer(model.cells(), spec)}}}, options.scale),
                      model.steps());
        };
        if (film && d.animation->shows(0)) film_frame();
        while (step_until_stop(model, stop))
            if (film && d.animation->shows(model.steps())) film_frame();
        if (film && !d.animation->shows(model.steps())) film_frame();  // the final state ends the film
        panels.push_back(
            {expand(d.panel_title, {{"n", std::to_string(runs[i].n)}, {"step", std::to_string(model.steps())}}),
             {field_layer(model.cells(), spec)}});
        panel_meta.push_back(panel_metadata(model, stop, true));
        progress.advance();
    }
    nlohmann::json meta = {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}};
    if (sink) meta["animation"] = sink->finish();
    write_figure(d, options,
                 draw_field_panels(panels, figure_width(d, options), figure_height(d, options), options.scale), meta);
    progress.finish();
}

}  // namespace figures
