// Elementary cellular automata side by side (Think Complexity 2e, Fig 7.6):
// rows are time, top to bottom, one panel per rule, drawn in Blues.
#include "figures/field_spec.hpp"
#include "figures/scene.hpp"
#include "render/digest.hpp"
#include "sim/cell1d.hpp"

namespace figures {

void render_cell1d(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"rules", "Wolfram rule numbers, one panel each, 0..255"},
                     {"width", "cells per row; 0: 2 * steps + 1, the book's default"},
                     {"boundary", "\"zero\" (the book's Cell1D) or \"wrap\" (its Wrap1D)"}});
    Settings style("style", d.style, field_spec_keys());
    if (d.panels.size() != 1)
        throw UsageError(d.id + ": figure.panels must hold one step, the last row shown (e.g. [31] for 32 rows)");
    std::vector<sim::Cell1DParams> automata;
    try {
        const auto boundary = sim::parse_boundary(params.text("boundary", "zero"));
        const int width = params.count("width", 0);
        for (long long rule : params.integers("rules", {20, 50, 18})) {
            sim::Cell1DParams p;
            p.rule = static_cast<int>(std::clamp<long long>(rule, -1, 256));
            p.rows = d.panels.front() + 1;
            p.width = width;
            p.boundary = boundary;
            p.validate();
            automata.push_back(p);
        }
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (automata.empty()) throw UsageError(d.id + ": params.rules is empty");
    const FieldSpec spec =
        read_field_spec(style, {render::colormap("Blues"), 0.0, 1.0, 0.7f, render::Sampling::nearest});
    progress.start(d.id, static_cast<long long>(automata.size()));

    // Each CA's rows (bytes) and the panel's field of them (doubles).
    const double rows = d.panels.front() + 1.0;
    require_drawable(d, "each automaton", rows, automata.front().width > 0 ? automata.front().width : 2.0 * rows + 1.0);
    require_memory(d, options,
                   {grid_need("rows of cells of a byte and a double", rows,
                              automata.front().width > 0 ? automata.front().width : 2.0 * rows + 1.0, 9,
                              double(automata.size()))});
    std::vector<FieldPanel> panels;
    nlohmann::json panel_meta = nlohmann::json::array();
    const int steps = d.panels.front();
    for (const auto& p : automata) {
        sim::Cell1D ca(p);
        for (int i = 0; i < steps; ++i) ca.step();
        const auto& cells = ca.cells();
        panels.push_back({expand(d.panel_title, {{"rule", std::to_string(p.rule)}, {"step", std::to_string(steps)}}),
                          {field_layer(cells, spec)}});
        panel_meta.push_back({{"rule", p.rule},
                              {"step", steps},
                              {"size", {cells.rows(), cells.cols()}},
                              {"statistics", {{"on_cells", ca.on_cells()}}},
                              {"state_sha256", render::sha256_hex(cells.data(), cells.size())}});
        progress.advance();
    }
    write_figure(d, options,
                 draw_field_panels(panels, figure_width(d, options), figure_height(d, options), options.scale),
                 {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}});
    progress.finish();
}

}  // namespace figures
