// Formula models (sim/formula/rule.hpp): a rule of the user's own, written as
// Ready writes its formula rules, run headless into panels and a film like
// any field figure. [params] holds the rule (chemicals, formula, accuracy,
// wrap, data_type, block_x, ready_edges), the grid (width, height), steps,
// the start (initial: Ready's overlays, in order) and, as every other key,
// the rule's own parameters; [style] says which chemicals each panel shows
// (show) and how (a_colormap, b_vmin, ... for each chemical). The model
// itself is read by scenes/helpers/formula_model.cpp.
//
// As a person looks at each grid: a 2-D grid as panels at the figure's
// steps; a 1-D grid as a space-time diagram per chemical shown (x across,
// steps down) beside the last step as a line plot; a 3-D grid as the
// active chemical's lit isosurface beside three slices through the centre.
#include "sim/formula/run.hpp"
#include "sim/formula/stability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <thread>

#include "base/digest.hpp"
#include "render/isosurface.hpp"
#include "render/tubes.hpp"
#include "ready/state.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/formula_model.hpp"
#include "scenes/helpers/formula_style.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"

namespace scenes {
namespace {

namespace formula = sim::formula;


// The grid as drawn with y = 0 at the bottom (Ready's y runs up the
// screen; a panel's row 0 is its top).
sim::Grid<double> flipped(const sim::Grid<double>& g) {
    sim::Grid<double> out(g.rows(), g.cols());
    for (int y = 0; y < g.rows(); ++y)
        std::copy(g.data() + static_cast<std::size_t>(y) * g.cols(), g.data() + static_cast<std::size_t>(y + 1) * g.cols(),
                  out.data() + static_cast<std::size_t>(g.rows() - 1 - y) * g.cols());
    return out;
}

class FormulaScene : public SceneBase {
public:
    FormulaScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, formula_param_keys(d),
                    formula_style_schema(formula_chemicals(d)).keys(formula_style_defaults(formula_chemicals(d)))),
          m_(read_formula_model(params_, d)),
          s_(formula_style_schema(m_.rule.chemicals).read(style_, formula_style_defaults(m_.rule.chemicals))),
          specs_(shown_specs(s_)) {
        if (d.panels.empty()) throw SettingError("figure.panels", "[]", "the steps to show, e.g. [0, 500, 1000]");
        if (d.panels.back() > m_.steps)
            throw SettingError("figure.panels", shown_steps(d.panels), "steps up to params.steps (" +
                                                                            std::to_string(m_.steps) + ")");
        // Without the film (--no-video) its steps are not run and not checked.
        if (options.film && d.animation && d.animation->last > m_.steps)
            throw SettingError("animation.steps", std::to_string(d.animation->last),
                               "steps up to params.steps (" + std::to_string(m_.steps) + ")");
        require_drawable(params_, "width", "the grid", m_.height, m_.width);
        if (d.animation && d.animation->turn_frames > 0 && dimensions_ != 3)
            throw SettingError("animation.turn_frames", std::to_string(d.animation->turn_frames),
                               "0: a " + std::to_string(dimensions_) +
                                   "-D grid has no 3-D view to turn (depth > 1 has)");
    }

    // Two states of every chemical, three on a 2-D grid (rows with their
    // halos and padding, sim/formula/run.cpp), each thread's registers (a chunk of at most
    // sim::formula::chunk_lanes cells each, a line apart), the start and the grids read at a
    // stop, and a copy per panel and frame of the chemicals shown, with
    // their textures.
    std::vector<MemoryNeed> memory() const override {
        const double cell = m_.rule.double_precision ? 8 : 4, chemicals = m_.rule.chemicals;
        const double panels = static_cast<double>(d_.panels.size()) + 1;
        const double row = m_.width + 2.0 * m_.radius_x + 64 / cell;  // a row, halos and padding
        const double threads = model_threads(false) > 0 ? model_threads(false) : std::max(1u, std::thread::hardware_concurrency());
        const double rows = static_cast<double>(m_.height) * m_.depth, shown = static_cast<double>(s_.shown.size());
        const double ghosts = formula_ghost_rows(m_);
        if (m_.kernel) return kernel_memory(threads, panels, shown);
        return {grid_need("the arrays a Ready pattern stores", rows, m_.width, 8, d_.stored_start ? chemicals : 0),
                grid_need("the chemicals' grids", rows + ghosts + 3, row, cell,
                          sim::formula::state_copies(m_.height, m_.depth, m_.rule.integrator) * chemicals),
                grid_need("the formula's registers", threads * (m_.registers + 1),
                          sim::formula::chunk_lanes + 64 / cell, cell, 1),
                grid_need("the formula's machine code", 1, m_.machine_code, 1, 1),
                grid_need("the start and the grids read", rows, m_.width, 8, 2 * chemicals),
                // --error: a run at a smaller timestep beside the figure's, and the three runs' last grids
                // (the figure's kept at its last panel, the two refined runs').
                grid_need("--error's run", rows + ghosts + 3, row, cell,
                          measures_error() ? sim::formula::state_copies(m_.height, m_.depth, m_.rule.integrator) * chemicals : 0),
                grid_need("--error's grids", rows, m_.width, 8, measures_error() ? 3 * chemicals : 0),
                // error = "space": the run at twice the resolution, its start and its grid read.
                grid_need("error's finer run", (rows + ghosts + 3) * finer_cells() / 2, 2 * row, cell,
                          measures_space_error() ? sim::formula::state_copies(m_.height, m_.depth, m_.rule.integrator) * chemicals : 0),
                grid_need("error's finer grids", rows * finer_cells(), m_.width, 8,
                          measures_space_error() ? 2 * chemicals : 0),
                grid_need("panels' copies", m_.height, m_.width, 8 + field_layer_bytes_per_cell, panels * shown),
                // A 1-D run's space-time diagram: its rows, and a copy drawn with its texture.
                grid_need("the space-time diagram", dimensions_ == 1 ? space_time_rows + 1 : 0, m_.width,
                          16 + field_layer_bytes_per_cell, shown),
                // A 3-D run's isosurface (the figure's and a frame's) with its corners as GL takes
                // them, the queue llvmpipe keeps, and the slices' copies.
                grid_need("the isosurface", 1, static_cast<double>(most_facets()),
                          sizeof(render::Facet) + 3 * 40.0, m_.depth > 1 ? 2 : 0),
                grid_need("the isosurface's draw queue", 1, render::queued_triangles_bytes, 1, m_.depth > 1 ? 1 : 0),
                grid_need("the slices", m_.depth, std::max(m_.width, m_.height), 8 + field_layer_bytes_per_cell,
                          m_.depth > 1 ? 3 : 0)};
    }

    // A kernel rule's run (sim/kernel/run.hpp): two buffers a chemical
    // and the writes' stamps, each thread's registers; the start, the
    // grids read, and what is drawn, as a formula's.
    std::vector<MemoryNeed> kernel_memory(double threads, double panels, double shown) const {
        const double rows = static_cast<double>(m_.height) * m_.depth, chemicals = m_.rule.chemicals;
        const long long cells = static_cast<long long>(m_.width) * m_.height * m_.depth;
        return {grid_need("the arrays a Ready pattern stores", rows, m_.width, 8, d_.stored_start ? chemicals : 0),
                grid_need("the kernel's buffers", 1, static_cast<double>(sim::kernel::run_bytes(*m_.kernel, cells)), 1, 1),
                grid_need("the kernel's registers", threads, static_cast<double>(m_.kernel_thread_bytes), 1, 1),
                grid_need("the start and the grids read", rows, m_.width, 8, 2 * chemicals),
                grid_need("panels' copies", m_.height, m_.width, 8 + field_layer_bytes_per_cell, panels * shown),
                grid_need("the space-time diagram", dimensions_ == 1 ? space_time_rows + 1 : 0, m_.width,
                          16 + field_layer_bytes_per_cell, shown),
                grid_need("the isosurface", 1, static_cast<double>(most_facets()),
                          sizeof(render::Facet) + 3 * 40.0, m_.depth > 1 ? 2 : 0),
                grid_need("the isosurface's draw queue", 1, render::queued_triangles_bytes, 1, m_.depth > 1 ? 1 : 0),
                grid_need("the slices", m_.depth, std::max(m_.width, m_.height), 8 + field_layer_bytes_per_cell,
                          m_.depth > 1 ? 3 : 0)};
    }

    // Every core (0), but one thread for a grid too small to share (4096
    // cells), or below 256^2 cells while film frames are drawn beside the
    // run. Ready's Pearson1993 at 128 x 64 without a film: 0.84 of rdy's
    // time on one thread, 0.45 on two (farm-bench, paired).
    int model_threads(bool filming = true) const {
        const long long cells = static_cast<long long>(m_.width) * m_.height * m_.depth;
        return cells < 4096 || (filming && cells < 65536) ? 1 : 0;
    }

    // --strict: a timestep past the explicit stability bound is refused
    // before anything runs (else render() says it on stderr).
    void check_run() const override {
        if (m_.kernel && options_.error)
            throw SettingError("--error", "", "none for a kernel rule: its kernel computes its own steps, so figgen "
                                              "cannot halve its timestep or its cells");
        if (!options_.strict || m_.kernel) return;
        const Bound b = bound(formula_start(m_, d_));
        const double timestep = m_.rule.parameter("timestep");
        if (timestep <= b.bound.timestep) return;
        const std::string integrator = formula::integrator_name(m_.rule.integrator);
        throw SettingError("params.timestep", format_number(timestep),
                           (b.bound.timestep > 0 ? "at most " + format_number(b.bound.timestep) +
                                                       ", the explicit stability bound of " + integrator
                                                 : "none under " + integrator + ": the modes' rates are imaginary") +
                               " here (" + b.why + "); a smaller timestep" +
                               (m_.rule.integrator == formula::Integrator::rk4 ? "" : ", or integrator = \"rk4\"") +
                               ", or without --strict");
    }

    void render(Output& out) const override {
        if (dimensions_ == 1) return render_line(out);
        if (m_.depth > 1) return render_solid(out);
        StepRunner run(d_, options_, out);
        const std::vector<sim::Grid<double>> start = formula_start(m_, d_);
        // A process that makes only film segments (another rank draws the figure) says nothing.
        const nlohmann::json stability = stability_said(start, !run.film_only());
        RuleRun model(m_, start);
        const int threads = model_threads(run.filming());
        std::vector<sim::Grid<double>> now, drawn;  // every chemical where the run is, and those shown as drawn
        std::vector<sim::Grid<double>> figure_state;  // at the figure's last panel, for error_said
        auto layers = [&](Cells cells) {
            std::vector<FieldLayer> l;
            for (std::size_t i = 0; i < s_.shown.size(); ++i) l.push_back(field_layer(drawn[i], specs_[i], cells));
            return l;
        };
        auto look = [&] {
            now.clear();
            for (int c = 0; c < m_.rule.chemicals; ++c) now.push_back(model.chemical(c));
            drawn.clear();
            for (int c : s_.shown) drawn.push_back(s_.upper ? plane(now[c]) : flipped(plane(now[c])));
        };
        look();
        std::vector<FieldPanel> panels;
        nlohmann::json panel_meta = nlohmann::json::array();
        run.run({
            .check = {},
            .panel =
                [&](int step) {
                    panels.push_back({format_step(d_.panel_title, step), layers(Cells::copied)});
                    panel_meta.push_back(metadata(now, step));
                    keep_for_error(step, now, figure_state);
                },
            .frame =
                [&](int step) -> FrameDrawing {
                    return run.field_frame({{format_step(d_.animation->title, step), layers(Cells::viewed)}});
                },
            .advance = {},
            .leap =
                [&](int steps) {
                    model.step(steps, threads);
                    look();
                },
        });
        nlohmann::json meta = {{"params", params_.used()},
                               {"style", style_.used()},
                               {"panels", panel_meta},
                               {"model_operations", model.operations()}};
        say_run(meta, stability, run, start, figure_state, threads);
        run.write_field_figure(panels, meta, [&] { return ready_state(now); });
    }

private:
    // The plane through the grid's centre (z = depth / 2) of a chemical's
    // cells: the grid itself in 2-D.
    sim::Grid<double> plane(const sim::Grid<double>& g) const {
        if (m_.depth == 1) return g;
        sim::Grid<double> out(m_.height, m_.width);
        const std::size_t from = static_cast<std::size_t>(m_.depth / 2) * m_.height * m_.width;
        std::copy(g.data() + from, g.data() + from + out.cells().size(), out.data());
        return out;
    }

    // The rows a 1-D run's space-time diagram keeps: every `stride`-th step
    // up to the last, at most space_time_rows of them.
    static constexpr int space_time_rows = 512;
    // The last step any output shows, whatever part of the film a run makes
    // (a run without the film may have been given one past params.steps).
    int figure_last() const {
        return std::max(d_.panels.back(), d_.animation ? std::min(d_.animation->last, m_.steps) : 0);
    }
    int space_time_stride() const { return scenes::space_time_stride(figure_last(), space_time_rows); }

    // Every chemical where the run is.
    std::vector<sim::Grid<double>> chemicals(const RuleRun& model) const {
        std::vector<sim::Grid<double>> all;
        for (int c = 0; c < m_.rule.chemicals; ++c) all.push_back(model.chemical(c));
        return all;
    }

    // A 1-D run (height 1): each chemical shown as a space-time diagram,
    // x across and the steps down, with real axes and its colour bar; and
    // every chemical shown at the step as a line plot. Films grow the
    // diagram as the run goes.
    struct SpaceTime {
        std::vector<std::vector<double>> rows;  // per chemical shown: its rows so far, one after another
        std::vector<int> steps;                 // the step of each row
    };

    void draw_line_page(render::Surface& surface, const SpaceTime& history, const std::vector<sim::Grid<double>>& now,
                        int step, int last, double scale) const {
        surface.background({1, 1, 1, 1});
        const render::PlotStyle style = plot_style(PlotSettings{}, scale);
        const int shown = static_cast<int>(s_.shown.size());
        const int rows = static_cast<int>(history.steps.size());
        // Each diagram's layer (its colours, range and bar), then the frames with room for the bars.
        std::vector<FieldLayer> layers;
        float bar_room = 0;
        for (int i = 0; i < shown; ++i) {
            sim::Grid<double> g(std::max(rows, 1), m_.width, 0.0);
            std::copy(history.rows[i].begin(), history.rows[i].end(), g.data());
            layers.push_back(field_layer(g, specs_[i]));
            if (layers.back().colour_bar)
                bar_room = std::max(bar_room, render::colour_bar_room(*layers.back().colour_bar,
                                                                      surface.width() / (shown + 1.0f),
                                                                      surface.height() * 0.7f, style));
        }
        const std::vector<render::Rect> frames =
            render::plot_row(surface.width(), surface.height(), shown + 1, style, 0, bar_room + 80 * float(scale));
        for (int i = 0; i < shown; ++i) {
            const render::Rect& f = frames[i];
            // The rows so far fill the frame's top; the steps still to come are blank.
            const float filled = last > 0 ? f.h * std::min(1.0f, float(history.steps.back() + std::max(1, space_time_stride())) /
                                                                     float(last + space_time_stride()))
                                          : f.h;
            if (rows > 0) surface.field({f.x, f.y, f.w, filled}, rows, m_.width, layers[i].values, layers[i].style);
            render::Axes axes;
            axes.x_range = {0.0, double(m_.width)};
            axes.y_range = {0.0, double(std::max(last, 1))};
            axes.y_down = true;
            axes.x_label = "x (cells)";
            axes.y_label = i == 0 ? "step" : "";
            axes.title = "chemical " + formula::chemical_name(s_.shown[i]);
            render::draw_axes(surface, f, axes, style);
            if (layers[i].colour_bar) render::draw_colour_bar(surface, f, *layers[i].colour_bar, style);
        }
        render::Axes plot;
        plot.x_range = {0.0, double(m_.width - 1)};
        plot.x_label = "x (cells)";
        plot.y_label = shown == 1 ? formula::chemical_name(s_.shown.front()) : "value";
        plot.title = format_step("step {step}", step);
        static const glm::vec4 palette[] = {{0.12f, 0.47f, 0.71f, 1}, {1.0f, 0.5f, 0.05f, 1},
                                            {0.17f, 0.63f, 0.17f, 1}, {0.84f, 0.15f, 0.16f, 1}};
        for (int i = 0; i < shown; ++i) {
            std::vector<double> x(static_cast<std::size_t>(m_.width)), y(x.size());
            for (int c = 0; c < m_.width; ++c) x[c] = c, y[c] = now[s_.shown[i]](0, c);
            plot.series.push_back(line_series(std::move(x), std::move(y), formula::chemical_name(s_.shown[i]),
                                              palette[i % 4], 1.5f, false));
        }
        if (shown > 1) plot.legend = render::Legend::upper_right;
        render::draw_axes(surface, frames.back(), plot, style);
    }

    void render_line(Output& out) const {
        StepRunner run(d_, options_, out);
        const std::vector<sim::Grid<double>> start = formula_start(m_, d_);
        // A process that makes only film segments (another rank draws the figure) says nothing.
        const nlohmann::json stability = stability_said(start, !run.film_only());
        RuleRun model(m_, start);
        const int threads = model_threads(run.filming());
        // The figure's last step, whatever part of the film this run makes
        // (a segment on another rank stops earlier): every frame's axes and
        // rows are the same on every rank.
        const int stride = space_time_stride(), last = figure_last();
        std::vector<sim::Grid<double>> now, figure_state;
        SpaceTime history;
        history.rows.resize(s_.shown.size());
        auto look = [&] { now = chemicals(model); };
        look();
        nlohmann::json panel_meta = nlohmann::json::array();
        run.run({
            .check =
                [&](int step) {
                    if (step % stride != 0 && step != last) return;
                    if (!history.steps.empty() && history.steps.back() == step) return;
                    for (std::size_t i = 0; i < s_.shown.size(); ++i)
                        history.rows[i].insert(history.rows[i].end(), now[s_.shown[i]].cells().begin(),
                                               now[s_.shown[i]].cells().end());
                    history.steps.push_back(step);
                },
            .panel =
                [&](int step) {
                    panel_meta.push_back(metadata(now, step));
                    keep_for_error(step, now, figure_state);
                },
            .frame =
                [&](int step) -> FrameDrawing {
                    return {[this, &history, &now, step, last](render::Surface& s) {
                                draw_line_page(s, history, now, step, last, options_.scale);
                            },
                            4, false};
                },
            .advance = {},
            .leap =
                [&](int steps) {
                    model.step(steps, threads);
                    look();
                },
            .stop_at = [stride](int step) { return step % stride == 0; },
        });
        nlohmann::json meta = {{"params", params_.used()},
                               {"style", style_.used()},
                               {"panels", panel_meta},
                               {"space_time", {{"rows", history.steps.size()}, {"stride", stride}}},
                               {"model_operations", model.operations()}};
        say_run(meta, stability, run, start, figure_state, threads);
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        const int shown_last = history.steps.empty() ? 0 : history.steps.back();
        FigureDrawing figure{width, height, false,
                             [this, &history, &now, shown_last](render::Surface& s) {
                                 draw_line_page(s, history, now, shown_last, shown_last, options_.scale);
                             },
                             [&] { return ready_state(now); }};
        run.write_figure(figure, meta);
    }

    // A 3-D run (depth above 1): the first chemical shown as its isosurface
    // at contour_level, lit, from a three-quarter view, inside the grid's
    // box; beside it three slices through the centre in its colours. The
    // film shows the isosurface.
    // A finer surface is sampled more coarsely: at most two facets a pixel
    // of the largest square it is drawn into (the figure's left half, a
    // film's frame).
    long long most_facets() const {
        const long long width = figure_width(d_, options_), height = figure_height(d_, options_);
        long long pixels = std::min(height, width / 2) * std::min(height, width / 2);
        if (d_.animation)
            pixels = std::max(pixels, static_cast<long long>(scaled_even(d_.animation->width, options_.scale)) *
                                          scaled_even(d_.animation->height, options_.scale));
        return render::facets_for_pixels(pixels);
    }

    std::vector<render::Facet> surface_of(const sim::Grid<double>& cells) const {
        const FieldSpec& spec = specs_.front();
        const double lo = spec.vmin.value_or(0.0), hi = spec.vmax.value_or(1.0);
        const double t = hi > lo ? (s_.contour_level - lo) / (hi - lo) : 0.5;
        const glm::vec4 colour(spec.colormap.at(std::clamp(t, 0.0, 1.0)), 1.0f);
        render::IsosurfaceGrid grid{m_.width, m_.height, m_.depth, cells.cells()};
        grid.inside_below = s_.contour_below;
        std::vector<render::Facet> facets = render::isosurface_within(grid, s_.contour_level, colour, most_facets());
        // The grid's z up on the page: world (x, z, -y), a rotation (windings keep their sense).
        auto turn = [](glm::vec3& v) { v = glm::vec3(v.x, v.z, -v.y); };
        for (render::Facet& f : facets)
            for (glm::vec3* v : {&f.a, &f.b, &f.c, &f.na, &f.nb, &f.nc}) turn(*v);
        return facets;
    }

    // `turned`: the part of a turn the camera has gone round the box (0 to 1), from the three-quarter view.
    void draw_solid(render::Surface& surface, const render::Rect& view, const std::vector<render::Facet>& facets,
                    double turned = 0) const {
        const glm::vec3 lo(0, 0, -float(m_.height - 1)), hi(float(m_.width - 1), float(m_.depth - 1), 0);
        // The box's twelve edges, thin and grey.
        const std::vector<render::Tube> edges = render::box_edges(
            lo, hi, 0.004f * float(std::max({m_.width, m_.height, m_.depth})), {0.55f, 0.55f, 0.55f, 1});
        render::Camera camera = render::frame_bounds(lo, hi, float(35 + 360 * turned), 25, view.w / view.h);
        if (turned > 0) {
            // Turning, the camera keeps the distance at which the box fits from every side.
            float distance = 0;
            for (int a = 0; a < 360; a += 5)
                distance = std::max(distance, glm::length(render::frame_bounds(lo, hi, float(a), 25, view.w / view.h).eye -
                                                          camera.target));
            camera.eye = camera.target + distance * glm::normalize(camera.eye - camera.target);
        }
        // Lit from over the viewer's left shoulder: every face the eye sees is lit, the ones
        // turned up and to the left the most.
        const glm::vec3 back = glm::normalize(camera.eye - camera.target);
        const glm::vec3 left = glm::normalize(glm::cross(back, camera.up));
        render::Light light;
        light.direction = 0.8f * back + 0.5f * camera.up + 0.3f * left;
        render::draw_tubes(surface, view, edges, facets, camera, light, 8);
    }

    // The three slices through the centre: z = depth/2 (x across, y up),
    // y = height/2 (x across, z up), x = width/2 (y across, z up).
    std::vector<FieldPanel> slices(const sim::Grid<double>& cells) const {
        const int w = m_.width, h = m_.height, d = m_.depth;
        auto at = [&](int x, int y, int z) { return cells(z * h + y, x); };
        sim::Grid<double> xy(h, w), xz(d, w), yz(d, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) xy(h - 1 - y, x) = at(x, y, d / 2);
        for (int z = 0; z < d; ++z)
            for (int x = 0; x < w; ++x) xz(d - 1 - z, x) = at(x, h / 2, z);
        for (int z = 0; z < d; ++z)
            for (int y = 0; y < h; ++y) yz(d - 1 - z, y) = at(w / 2, y, z);
        return {{"z = " + std::to_string(d / 2), {field_layer(xy, specs_.front())}},
                {"y = " + std::to_string(h / 2), {field_layer(xz, specs_.front())}},
                {"x = " + std::to_string(w / 2), {field_layer(yz, specs_.front())}}};
    }

    void render_solid(Output& out) const {
        StepRunner run(d_, options_, out);
        const std::vector<sim::Grid<double>> start = formula_start(m_, d_);
        // A process that makes only film segments (another rank draws the figure) says nothing.
        const nlohmann::json stability = stability_said(start, !run.film_only());
        RuleRun model(m_, start);
        const int threads = model_threads(run.filming());
        std::vector<sim::Grid<double>> now, figure_state;
        auto look = [&] { now = chemicals(model); };
        look();
        nlohmann::json panel_meta = nlohmann::json::array();
        run.run({
            .check = {},
            .panel =
                [&](int step) {
                    panel_meta.push_back(metadata(now, step));
                    keep_for_error(step, now, figure_state);
                },
            .frame =
                [&](int) -> FrameDrawing {
                    auto facets = std::make_shared<const std::vector<render::Facet>>(surface_of(now[s_.shown.front()]));
                    return {[this, facets](render::Surface& s) {
                                s.background({1, 1, 1, 1});
                                draw_solid(s, {0, 0, float(s.width()), float(s.height())}, *facets);
                            },
                            4, true};
                },
            .advance = {},
            .leap =
                [&](int steps) {
                    model.step(steps, threads);
                    look();
                },
            // The last step's surface, made once, seen from round the box.
            .turn =
                [&, last = std::shared_ptr<const std::vector<render::Facet>>()](int k, int n) mutable -> FrameDrawing {
                    if (!last) last = std::make_shared<const std::vector<render::Facet>>(surface_of(now[s_.shown.front()]));
                    const double turned = double(k + 1) / n;
                    return {[this, facets = last, turned](render::Surface& s) {
                                s.background({1, 1, 1, 1});
                                draw_solid(s, {0, 0, float(s.width()), float(s.height())}, *facets, turned);
                            },
                            4, true};
                },
        });
        const std::vector<render::Facet> facets = surface_of(now[s_.shown.front()]);
        const std::vector<FieldPanel> panels = slices(now[s_.shown.front()]);
        nlohmann::json meta = {{"params", params_.used()},
                               {"style", style_.used()},
                               {"panels", panel_meta},
                               {"isosurface",
                                {{"level", s_.contour_level},
                                 {"inside", s_.contour_below ? "below" : "above"},
                                 {"facets", facets.size()}}},
                               {"model_operations", model.operations()}};
        say_run(meta, stability, run, start, figure_state, threads);
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        const double scale = options_.scale;
        FigureDrawing figure{width, height, true,
                             [this, &facets, &panels, scale](render::Surface& s) {
                                 s.background({1, 1, 1, 1});
                                 const float side = std::min(float(s.height()), 0.5f * float(s.width()));
                                 draw_solid(s, {0, (float(s.height()) - side) / 2, side, side}, facets);
                                 draw_field_panels(s, {side, 0, float(s.width()) - side, float(s.height())}, panels, 2,
                                                   scale);
                             },
                             [&] { return ready_state(now); }};
        run.write_figure(figure, meta);
    }

    // The explicit stability bound on the timestep for the rule's
    // integrator (sim/formula/stability.hpp), linearised about the start's
    // mean: said on stderr before the run when the timestep is past it, and
    // in the metadata. The run still stops at the first value that is not
    // finite.
    static std::string format_number(double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.4g", v);
        return text;
    }

    // The bound about the start's mean, and where it comes from: "chemical
    // a's stencil terms, the mode theta = (1 pi, 1 pi)".
    struct Bound {
        formula::StabilityBound bound;
        std::string why;
    };
    Bound bound(const std::vector<sim::Grid<double>>& start) const {
        std::vector<double> mean;
        for (const auto& g : start) mean.push_back(field_statistics(g)["mean"].get<double>());
        Bound b{formula::stability_bound(m_.rule, dimensions_, mean), ""};
        std::string theta;
        for (double t : b.bound.theta) theta += (theta.empty() ? "" : ", ") + format_number(t / M_PI) + " pi";
        b.why = "chemical " + b.bound.chemical + "'s stencil terms, the mode theta = (" + theta + ")";
        return b;
    }

    // The edges the run computes: Ready's (with its wrap), or figgen's own
    // side by side, for the sides of the grid's axes.
    nlohmann::json edges_said() const {
        if (m_.kernel) return {{"kernel", "the kernel's own: it indexes its neighbours itself"}};
        const formula::Rule& r = m_.rule;
        if (r.ready_edges && !r.edges) return {{"ready", true}, {"wrap", r.wrap}};
        const formula::Edges e = r.own_edges();
        const int sizes[3] = {m_.width, m_.height, m_.depth};
        nlohmann::json said = nlohmann::json::object();
        for (int side = 0; side < 6; ++side) {
            if (sizes[side / 2] == 1) continue;
            const formula::Edges::Of& of = e.side[static_cast<std::size_t>(side)];
            said[formula::side_name(side)] = of.edge == formula::Edge::dirichlet
                                                 ? nlohmann::json{{"edge", "dirichlet"}, {"value", of.value}}
                                                 : nlohmann::json{{"edge", formula::edge_name(of.edge)}};
        }
        return said;
    }

    bool measures_error() const { return m_.error != FormulaModel::Error::none || options_.error; }

    // The chemicals at the figure's last panel, kept where the error is measured.
    void keep_for_error(int step, const std::vector<sim::Grid<double>>& now,
                        std::vector<sim::Grid<double>>& kept) const {
        if (measures_error() && step == d_.panels.back()) kept = now;
    }

    // What each formula figure's metadata says of its run besides its
    // panels: the stability bound, the edges, and (--error) the error
    // measured, by the process that draws the figure.
    void say_run(nlohmann::json& meta, const nlohmann::json& stability, const StepRunner& run,
                 const std::vector<sim::Grid<double>>& start, const std::vector<sim::Grid<double>>& figure_state,
                 int threads) const {
        meta["stability"] = stability;
        meta["edges"] = edges_said();
        if (measures_error() && !run.film_only() && !figure_state.empty())
            meta["error"] = error_said(start, figure_state, threads);
    }
    bool measures_space_error() const { return m_.error == FormulaModel::Error::space; }
    // The cells of the grid at twice the resolution, over the grid's.
    double finer_cells() const { return (m_.height > 1 ? 4.0 : 2.0) * (m_.depth > 1 ? 2.0 : 1.0); }

    // error = "space": the run again at twice the resolution (dx / 2) and a
    // quarter of the timestep (so that a diffusion's explicit bound holds,
    // and forward Euler's error in time falls as a second-order stencil's
    // in space), to the same time; each cell against the mean of the finer
    // run's cells on its square. Richardson's estimate with the order 2 of
    // Ready's low and medium stencils: d 4 / 3.
    nlohmann::json space_error_said(const std::vector<sim::Grid<double>>& figure, int threads) const {
        const int step = d_.panels.back();
        FormulaModel fine = m_;
        const int fx = 2, fy = m_.height > 1 ? 2 : 1, fz = m_.depth > 1 ? 2 : 1;
        fine.width *= fx;
        fine.height *= fy;
        fine.depth *= fz;
        const double h = m_.rule.parameter("timestep"), dx = m_.rule.parameter("dx", 1.0);
        fine.rule.set_parameter("timestep", h / 4);
        fine.rule.set_parameter("dx", dx / 2);
        // The finer cells half a finer cell back: each pair's mean is where the coarser cell is.
        const std::array<double, 3> offset{-0.5, fy > 1 ? -0.5 : 0.0, fz > 1 ? -0.5 : 0.0};
        formula::Run run(fine.rule, fine.width, fine.height, fine.depth, formula_start(fine, d_, offset));
        try {
            run.step(step * 4, threads);
        } catch (const formula::Unstable& e) {
            throw formula::Unstable("--error's run at twice the resolution: " + std::string(e.what()));
        }
        nlohmann::json chemicals_said = nlohmann::json::array();
        for (int c = 0; c < m_.rule.chemicals; ++c) {
            const sim::Grid<double> finer = run.chemical(c);
            const sim::Grid<double>& coarse = figure[static_cast<std::size_t>(c)];
            double most = 0, squares = 0;
            for (int z = 0; z < m_.depth; ++z)
                for (int y = 0; y < m_.height; ++y)
                    for (int x = 0; x < m_.width; ++x) {
                        double mean = 0;
                        for (int k = 0; k < fz; ++k)
                            for (int j = 0; j < fy; ++j)
                                for (int i = 0; i < fx; ++i)
                                    mean += finer((z * fz + k) * fine.height + y * fy + j, x * fx + i);
                        mean /= fx * fy * fz;
                        const double d = coarse(z * m_.height + y, x) - mean;
                        most = std::max(most, std::abs(d));
                        squares += d * d;
                    }
            const double rms = std::sqrt(squares / (static_cast<double>(m_.width) * m_.height * m_.depth));
            chemicals_said.push_back({{"chemical", formula::chemical_name(c)},
                                      {"largest", most},
                                      {"rms", rms},
                                      {"estimate", {{"largest", most * 4 / 3}, {"rms", rms * 4 / 3}}}});
        }
        return {{"method", "the run again at twice the resolution (dx / 2, timestep / 4) to the figure's last "
                           "panel, each cell against the mean of the finer cells on its square"},
                {"grid", {fine.width, fine.height, fine.depth}},
                {"dx", {dx, dx / 2}},
                {"timesteps", {h, h / 4}},
                {"order", 2},
                {"chemicals", chemicals_said}};
    }

    // --error (or [params] error): the figure's error in time, measured. The
    // run again from the same start at half and a quarter of the timestep
    // to the time of the figure's last panel; for each chemical the largest
    // and the RMS difference over the cells between the timesteps h and
    // h/2 (d1) and h/2 and h/4 (d2), the observed order log2(d1 / d2), and
    // Richardson's estimate of the figure's own error, d1 2^q / (2^q - 1)
    // with q the integrator's order (u_h - u = C h^q + ...). Where d2 is
    // within rounding of the values the order is not said.
    nlohmann::json error_said(const std::vector<sim::Grid<double>>& start,
                              const std::vector<sim::Grid<double>>& figure, int threads) const {
        const int step = d_.panels.back();
        const double h = m_.rule.parameter("timestep");
        const int q = formula::order(m_.rule.integrator);
        // The runs at h (the figure's), h / 2 and h / 4.
        std::vector<sim::Grid<double>> refined[2];
        auto runs = [&](int k) -> const std::vector<sim::Grid<double>>& { return k == 0 ? figure : refined[k - 1]; };
        for (int k : {2, 4}) {
            FormulaModel finer = m_;
            finer.rule.set_parameter("timestep", h / k);
            RuleRun run(finer, start);
            try {
                run.step(step * k, threads);
            } catch (const formula::Unstable& e) {
                throw formula::Unstable(std::string("--error's run at timestep ") + format_number(h / k) + ": " +
                                        e.what());
            }
            refined[k / 4] = chemicals(run);
        }
        const double epsilon = m_.rule.double_precision ? 0x1p-52 : 0x1p-23;
        nlohmann::json chemicals_said = nlohmann::json::array();
        for (int c = 0; c < m_.rule.chemicals; ++c) {
            double most[2] = {0, 0}, squares[2] = {0, 0}, largest = 0;
            const std::size_t cells = figure[static_cast<std::size_t>(c)].cells().size();
            for (int k = 0; k < 2; ++k) {
                const auto& a = runs(k)[static_cast<std::size_t>(c)].cells();
                const auto& b = runs(k + 1)[static_cast<std::size_t>(c)].cells();
                for (std::size_t i = 0; i < cells; ++i) {
                    const double d = a[i] - b[i];
                    most[k] = std::max(most[k], std::abs(d));
                    squares[k] += d * d;
                    largest = std::max(largest, std::abs(a[i]));
                }
            }
            const double rms[2] = {std::sqrt(squares[0] / static_cast<double>(cells)),
                                   std::sqrt(squares[1] / static_cast<double>(cells))};
            // Steps' rounding: each of the finest run's steps may round a value by epsilon.
            const double rounding = epsilon * std::max(1.0, largest) * std::sqrt(4.0 * std::max(step, 1));
            const double factor = std::ldexp(1.0, q) / (std::ldexp(1.0, q) - 1);
            nlohmann::json said = {{"chemical", formula::chemical_name(c)},
                                   {"largest", {most[0], most[1]}},
                                   {"rms", {rms[0], rms[1]}},
                                   {"estimate", {{"largest", factor * most[0]}, {"rms", factor * rms[0]}}}};
            const bool measurable = most[1] > 10 * rounding && most[0] > 0;
            said["order"] = measurable ? nlohmann::json(std::log2(most[0] / most[1])) : nlohmann::json(nullptr);
            said["order_rms"] =
                measurable && rms[1] > 0 ? nlohmann::json(std::log2(rms[0] / rms[1])) : nlohmann::json(nullptr);
            if (!measurable) said["rounding"] = "the differences are within the number type's rounding: no order";
            chemicals_said.push_back(said);
        }
        nlohmann::json said = {{"method", "the run again at timestep / 2 and / 4 to the figure's last panel, cell by cell"},
                               {"step", step},
                               {"time", step * h},
                               {"timesteps", {h, h / 2, h / 4}},
                               {"integrator", formula::integrator_name(m_.rule.integrator)},
                               {"order", q},
                               {"chemicals", chemicals_said}};
        if (measures_space_error()) said["space"] = space_error_said(figure, threads);
        return said;
    }

    nlohmann::json stability_said(const std::vector<sim::Grid<double>>& start, bool say = true) const {
        if (m_.kernel)
            return {{"bound", nullptr},
                    {"why", "a kernel rule computes its own steps: figgen bounds none, and stops the run at the "
                            "first number that is not finite"}};
        const Bound said_bound = bound(start);
        const formula::StabilityBound& b = said_bound.bound;
        const double timestep = m_.rule.parameter("timestep");
        const char* integrator = formula::integrator_name(m_.rule.integrator);
        nlohmann::json said = {{"integrator", integrator}, {"timestep", timestep}};
        if (std::isinf(b.timestep)) {
            said["bound"] = nullptr;
            said["within"] = true;
            said["why"] = "the deltas read no neighbour: no bound from the stencils";
            return said;
        }
        said["bound"] = b.timestep;
        said["within"] = timestep <= b.timestep;
        said["chemical"] = b.chemical;
        said["mode"] = b.theta;
        said["rate"] = {b.rate_real, b.rate_imaginary};
        if (b.coupled) said["coupled"] = "three chemicals or more whose stencil terms reach into each other: the bound is from each one's own";
        if (say && timestep > b.timestep) {
            std::cerr << "figgen: warning: " << d_.id << ": timestep " << format_number(timestep);
            if (b.timestep > 0)
                std::cerr << " is past the explicit stability bound " << format_number(b.timestep) << " of "
                          << integrator;
            else
                std::cerr << ": no timestep is stable under " << integrator
                          << " (the modes' rates are imaginary: try integrator = \"rk4\")";
            std::cerr << " here (" << said_bound.why << "); the run may blow up\n";
        }
        return said;
    }

    // The chemicals and the rule, for Ready's own files (--format vti).
    ready::ReadyState ready_state(const std::vector<sim::Grid<double>>& chemicals) const {
        ready::ReadyState s;
        s.rule_name = d_.title;
        s.description = d_.caption;
        s.formula = m_.rule.code;
        if (m_.kernel) s.kernel = m_.kernel->text;
        static const char* accuracy[] = {"low", "medium", "high"};
        s.accuracy = accuracy[static_cast<int>(m_.rule.accuracy)];
        // Ready has wrapped or clamped edges alone: figgen's own edges go as wrapped where x's are periodic.
        s.wrap = m_.rule.edges ? m_.rule.edges->side[formula::left].edge == formula::Edge::periodic : m_.rule.wrap;
        s.block_x = m_.rule.block_x;
        s.parameters = m_.rule.parameters;
        s.active_chemical = formula::chemical_name(s_.shown.front());
        s.low = specs_.front().vmin;
        s.high = specs_.front().vmax;
        s.width = m_.width;
        s.height = m_.height;
        s.depth = m_.depth;
        s.float64 = m_.rule.double_precision;
        for (const auto& g : chemicals) s.chemicals.emplace_back(g.cells().begin(), g.cells().end());
        return s;
    }

    nlohmann::json metadata(const std::vector<sim::Grid<double>>& chemicals, int step) const {
        nlohmann::json stats = nlohmann::json::object();
        std::vector<base::Bytes> state;  // the chemicals one after another
        for (int c = 0; c < m_.rule.chemicals; ++c) {
            auto s = field_statistics(chemicals[c]);
            s.erase("sum");
            stats[formula::chemical_name(c)] = s;
            state.push_back({chemicals[c].data(), chemicals[c].size() * sizeof(double)});
        }
        return {{"step", step}, {"statistics", stats}, {"state_sha256", base::sha256_hex(state)}};
    }

    const FormulaModel m_;
    const FormulaStyle s_;
    const std::vector<FieldSpec> specs_;  // of the chemicals shown
    const int dimensions_ = formula::dimensionality(m_.width, m_.height, m_.depth);
};

std::unique_ptr<Scene> read_formula(const Description& d, const SceneOptions& options) {
    return std::make_unique<FormulaScene>(d, options);
}

}  // namespace

// A formula figure's chemicals a .. z each have a colormap.
static std::vector<std::string> formula_colormap_keys() {
    std::vector<std::string> keys;
    for (char c = 'a'; c <= 'z'; ++c) keys.push_back(std::string(1, c) + "_colormap");
    return keys;
}

// Only the chemicals of the description's rule.
static std::vector<std::string> rule_colormap_keys(const Description& d) {
    std::vector<std::string> keys = formula_colormap_keys();
    keys.resize(static_cast<std::size_t>(formula_chemicals(d)));
    return keys;
}

// The most the VTI file of the last step takes: every chemical's cells as
// doubles in base64 (zlib's blocks can only grow by a few bytes each), and
// the XML around them with the rule's name, description and formula.
static double vti_disk(const Description& d) {
    const auto value = [&](const char* key, long long fallback, long long most) {
        return static_cast<double>(std::clamp<long long>(d.params[key].value_or(fallback), 1, most));
    };
    const double cells = value("width", 128, formula_most_side) * value("height", 128, formula_most_side) *
                         value("depth", 1, formula_most_side);
    // The texts it repeats (XML escapes a character in at most 6: &quot;).
    const double texts = static_cast<double>(d.title.size() + d.caption.size() +
                                             d.params["formula"].value_or(std::string()).size());
    // And each parameter's element: its name (counted in the formula) and value.
    return cells * formula_chemicals(d) * 8 * 1.34 * 1.01 + 65536 + 6 * texts + 200.0 * d.params.size();
}

SceneInfo formula_scene() {
    return {.name = "formula",
            .read = read_formula,
            .colormap_keys = formula_colormap_keys(),
            // With --error, the card says the figure's measured error in time.
            .key_numbers = {{"/error/chemicals/*/estimate/largest", "error in time of {chemical}, largest (Richardson)",
                             "number", "", {}, "", "", 2},
                            {"/error/chemicals/*/order", "observed order in time of {chemical}", "number", "", {}, "",
                             "", 3},
                            {"/error/space/chemicals/*/estimate/largest",
                             "error in space of {chemical}, largest (Richardson, order 2)", "number", "", {}, "", "", 2}},
            .colormap_keys_of = rule_colormap_keys,
            .extra_files = {{.format = "vti", .disk = vti_disk}},
            .turns = true};
}

}  // namespace scenes
