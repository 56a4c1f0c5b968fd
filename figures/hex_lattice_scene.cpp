// Liu & Zhang 1987, Fig 2: the lattices of the paper's automata, a 1-D row
// of cells and a 2-D hexagonal patch with the centre 0 and its neighbours
// 1..6 numbered as in the paper's equation (2). A schematic: no model runs.
#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "render/hex_cells.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"

namespace figures {

void render_hex_lattice(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"row_cells", "cells in the 1-D row, odd"}, {"radius", "rings of the hexagonal patch"}});
    Settings style("style", d.style,
                   {{"line_colour", "cell outlines"},
                    {"fill_colour", "the centre and its neighbours"},
                    {"captions", "captions of the two panels"}});
    const int row_cells = params.count("row_cells", 7);
    const int radius = params.count("radius", 2);
    if (row_cells < 3 || row_cells > 41 || row_cells % 2 == 0)
        throw UsageError(d.id + ": params.row_cells = " + std::to_string(row_cells) +
                         " is not allowed: an odd number 3..41");
    if (radius < 1 || radius > 10)
        throw UsageError(d.id + ": params.radius = " + std::to_string(radius) + " is not allowed: 1..10");
    const glm::vec4 line = style_colour(style, "line_colour", "black");
    const glm::vec4 fill = style_colour(style, "fill_colour", "#dde8f3");
    const auto captions = style.texts("captions", {"(a) one-dimensional", "(b) two-dimensional (hexagonal)"});
    if (captions.size() != 2) throw UsageError(d.id + ": style.captions must hold two captions");
    progress.start(d.id, 1);

    const float s = static_cast<float>(options.scale);
    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    render::Font label_font(std::round(16 * s)), caption_font(std::round(17 * s));
    render::Text text;
    render::Shapes fills, outlines;
    const float caption_band = 40 * s;
    const float half = float(width) / 2;
    const glm::vec4 black{0, 0, 0, 1};

    // (a) a row of square cells; the middle one and its two neighbours named.
    const float cell = std::min((half - 40 * s) / float(row_cells), (float(height) - caption_band) / 3);
    const float row_y = (float(height) - caption_band) / 2 - cell / 2;
    const float row_x = (half - cell * float(row_cells)) / 2;
    const int mid = row_cells / 2;
    std::vector<double> row_state, patch_state;  // what each panel is drawn from: cell rects, hex cells and centres
    for (int i = 0; i < row_cells; ++i) {
        const render::Rect r{row_x + float(i) * cell, row_y, cell, cell};
        row_state.insert(row_state.end(), {r.x, r.y, r.w, r.h, double(std::abs(i - mid) <= 1)});
        if (std::abs(i - mid) <= 1) fills.rect(r, fill);
        outlines.frame(r, 1.5f * s, line);
        if (std::abs(i - mid) <= 1)
            text.add(label_font,
                     i == mid  ? "i"
                     : i < mid ? "i\u22121"
                               : "i+1",
                     r.centre(), black, render::Align::centre, render::Baseline::middle);
    }
    text.add(caption_font, captions[0], {half / 2, float(height) - caption_band / 2}, black, render::Align::centre,
             render::Baseline::middle);

    // (b) a hexagonal patch; the paper's cell 0 and neighbours 1..6.
    const render::Rect patch{half + 20 * s, 20 * s, half - 40 * s, float(height) - caption_band - 30 * s};
    const auto view = render::fit_hex_view(patch, radius);
    // Neighbour k at 30 + 60 (k - 1) degrees, counter-clockwise from the right.
    const glm::ivec2 numbered[7] = {{0, 0}, {1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}};
    std::vector<glm::ivec2> filled(std::begin(numbered), std::end(numbered));
    render::draw_hex_cells(canvas, view, filled, fill);
    for (int q = -radius; q <= radius; ++q)
        for (int r = -radius; r <= radius; ++r)
            if (std::max({std::abs(q), std::abs(r), std::abs(q + r)}) <= radius) {
                render::hex_outline(outlines, view, {q, r}, 1.5f * s, line);
                const glm::vec2 centre = render::hex_centre(view, {q, r});
                patch_state.insert(patch_state.end(), {double(q), double(r), centre.x, centre.y, view.size});
            }
    for (const auto& c : filled) patch_state.insert(patch_state.end(), {double(c.x), double(c.y)});
    for (int k = 0; k < 7; ++k)
        text.add(label_font, std::to_string(k), render::hex_centre(view, numbered[k]), black, render::Align::centre,
                 render::Baseline::middle);
    text.add(caption_font, captions[1], {half + half / 2, float(height) - caption_band / 2}, black,
             render::Align::centre, render::Baseline::middle);

    fills.draw(canvas);
    outlines.draw(canvas);
    text.draw(canvas);
    write_figure(d, options, canvas.read(),
                 {{"params", params.used()},
                  {"style", style.used()},
                  {"panels",
                   {{{"label", "(a)"}, {"cells", row_cells}, {"state_sha256", state_hash(row_state)}},
                    {{"label", "(b)"}, {"rings", radius}, {"state_sha256", state_hash(patch_state)}}}}});
    progress.finish();
}

}  // namespace figures
