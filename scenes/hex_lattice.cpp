// Liu & Zhang 1987, Fig 2: the lattices of the paper's automata, a 1-D row
// of cells and a 2-D hexagonal patch with the centre 0 and its neighbours
// 1..6 numbered as in the paper's equation (2). A schematic: no model runs.
#include "render/hex_cells.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"

namespace scenes {
namespace {

struct Params {
    int row_cells = 7, radius = 2;
};

const Schema<Params> param_schema =
    Schema<Params>()
        .key({"row_cells", "cells in the 1-D row", "an integer", "an odd number from 3 to 41", 7},
             [](Settings& s, const std::string& key, Params& p) {
                 p.row_cells = s.count(key, p.row_cells);
                 if (p.row_cells < 3 || p.row_cells > 41 || p.row_cells % 2 == 0)
                     s.refuse(key, "an odd number from 3 to 41");
             })
        .count("radius", &Params::radius, "rings of the hexagonal patch", 1, 10);

struct Style {
    Colour line = colour("black"), fill = colour("#dde8f3");
    std::vector<std::string> captions{"(a) one-dimensional", "(b) two-dimensional (hexagonal)"};
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"line_colour", "cell outlines", "a colour"}, &Style::line, read_colour)
        .field({"fill_colour", "the centre and its neighbours", "a colour"}, &Style::fill, read_colour)
        .key(
            {"captions", "captions of the two panels", "a list of strings", "two captions, (a)'s and (b)'s"},
            [](Settings& s, const std::string& key, Style& v) {
                v.captions = s.texts(key, v.captions);
                if (v.captions.size() != 2) s.refuse(key, "two captions, (a)'s and (b)'s");
            },
            [](const Style& d) { return nlohmann::json(d.captions); });

// What both panels draw into: cells, shapes and text gathered, drawn at the end.
struct Drawing {
    Drawing(int width_, int height_, float scale)
        : s(scale),
          width(width_),
          height(height_),
          caption_band(40 * s),
          half(float(width) / 2),
          label_font(std::round(16 * s)),
          caption_font(std::round(17 * s)) {}

    const float s;  // the output scale
    const int width, height;
    const float caption_band, half;
    render::Font label_font, caption_font;
    render::Text text;
    render::PageText page;  // where the text went, for its fit check
    render::HexView view;
    std::vector<glm::ivec2> cells;  // filled with the scene's fill colour, under the rest
    render::Shapes fills, outlines;

    // A shape text must keep clear of, or stay inside: its index on the page.
    int shape(const render::Rect& where, std::string what) {
        page.panels.push_back({where, std::move(what)});
        return static_cast<int>(page.panels.size()) - 1;
    }
    // A line of text centred on `at`, inside shape `within` (-1: clear of every shape).
    void label(render::Font& font, const std::string& line, glm::vec2 at, std::string what, int within = -1) {
        const glm::vec4 black{0, 0, 0, 1};
        text.add(font, line, at, black, render::Align::centre, render::Baseline::middle);
        const render::LineInk ink = render::line_ink(font, line, at, render::Align::centre, render::Baseline::middle);
        page.texts.push_back({ink.box, std::move(what), within, ink.glyphs, ink.em});
    }
};

class HexLatticeScene : public SceneBase {
public:
    HexLatticeScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)) {
        refuse_steps(d, "a schematic has no steps", true);
        require_text_fits(d, options, [&](const render::Rect& area) {
            Drawing draw(static_cast<int>(area.w), static_cast<int>(area.h), static_cast<float>(options.scale));
            draw_row(draw);
            draw_patch(draw);
            return std::move(draw.page);
        }, "shorten style.captions");
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, 1);
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        Drawing draw(width, height, static_cast<float>(options_.scale));
        const std::vector<double> row_state = draw_row(draw);
        const std::vector<double> patch_state = draw_patch(draw);
        const FigureDrawing figure{width, height, false, [this, &draw](render::Surface& surface) {
                                       surface.background({1, 1, 1, 1});
                                       render::draw_hex_cells(surface, draw.view, draw.cells, s_.fill.rgba);
                                       draw.fills.draw(surface);
                                       draw.outlines.draw(surface);
                                       draw.text.draw(surface);
                                   }};
        out.figure(figure, {{"params", params_.used()},
                            {"style", style_.used()},
                            {"panels",
                             {{{"label", "(a)"}, {"cells", p_.row_cells}, {"state_sha256", state_hash(row_state)}},
                              {{"label", "(b)"}, {"rings", p_.radius}, {"state_sha256", state_hash(patch_state)}}}}});
        progress.finish();
    }

private:
    // (a) a row of square cells; the middle one and its two neighbours named.
    // Returns what it is drawn from: each cell's rect and whether it is named.
    std::vector<double> draw_row(Drawing& draw) const {
        const float s = draw.s, half = draw.half, height = float(draw.height);
        const float cell = std::min((half - 40 * s) / float(p_.row_cells), (height - draw.caption_band) / 3);
        const float row_y = (height - draw.caption_band) / 2 - cell / 2;
        const float row_x = (half - cell * float(p_.row_cells)) / 2;
        const int mid = p_.row_cells / 2;
        draw.shape({row_x, row_y, cell * float(p_.row_cells), cell}, "the row of cells of (a)");
        std::vector<double> row_state;
        for (int i = 0; i < p_.row_cells; ++i) {
            const render::Rect r{row_x + float(i) * cell, row_y, cell, cell};
            row_state.insert(row_state.end(), {r.x, r.y, r.w, r.h, double(std::abs(i - mid) <= 1)});
            if (std::abs(i - mid) <= 1) draw.fills.rect(r, s_.fill.rgba);
            draw.outlines.frame(r, 1.5f * s, s_.line.rgba);
            if (std::abs(i - mid) <= 1) {
                const std::string name = i == mid ? "i" : i < mid ? "i\u22121" : "i+1";
                draw.label(draw.label_font, name, r.centre(), "the label " + name + " of (a)",
                           draw.shape(r, "its cell"));
            }
        }
        draw.label(draw.caption_font, s_.captions[0], {half / 2, height - draw.caption_band / 2}, "the caption of (a)");
        return row_state;
    }

    // (b) a hexagonal patch; the paper's cell 0 and neighbours 1..6. Returns
    // what it is drawn from: the hex cells and their centres, the filled cells.
    std::vector<double> draw_patch(Drawing& draw) const {
        const float s = draw.s, half = draw.half, height = float(draw.height);
        const render::Rect patch{half + 20 * s, 20 * s, half - 40 * s, height - draw.caption_band - 30 * s};
        const auto view = render::fit_hex_view(patch, p_.radius);
        draw.shape(patch, "the hexagons of (b)");
        // Neighbour k at 30 + 60 (k - 1) degrees, counter-clockwise from the right.
        const glm::ivec2 numbered[7] = {{0, 0}, {1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}};
        std::vector<glm::ivec2> filled(std::begin(numbered), std::end(numbered));
        draw.view = view;
        draw.cells = filled;
        std::vector<double> patch_state;
        for (int q = -p_.radius; q <= p_.radius; ++q)
            for (int r = -p_.radius; r <= p_.radius; ++r)
                if (std::max({std::abs(q), std::abs(r), std::abs(q + r)}) <= p_.radius) {
                    render::hex_outline(draw.outlines, view, {q, r}, 1.5f * s, s_.line.rgba);
                    const glm::vec2 centre = render::hex_centre(view, {q, r});
                    patch_state.insert(patch_state.end(), {double(q), double(r), centre.x, centre.y, view.size});
                }
        for (const auto& c : filled) patch_state.insert(patch_state.end(), {double(c.x), double(c.y)});
        for (int k = 0; k < 7; ++k) {
            // The square inside the hexagon's inscribed circle (radius sqrt(3)/2 of its circumradius).
            const glm::vec2 c = render::hex_centre(view, numbered[k]);
            const float half_side = 0.8660254f * view.size / 1.4142136f;
            const int inside = draw.shape({c.x - half_side, c.y - half_side, 2 * half_side, 2 * half_side}, "its hexagon");
            draw.label(draw.label_font, std::to_string(k), c, "the label " + std::to_string(k) + " of (b)", inside);
        }
        draw.label(draw.caption_font, s_.captions[1], {half + half / 2, height - draw.caption_band / 2},
                   "the caption of (b)");
        return patch_state;
    }

    const Params p_;
    const Style s_;
};

std::unique_ptr<Scene> read_hex_lattice(const Description& d, const SceneOptions& options) {
    return std::make_unique<HexLatticeScene>(d, options);
}

}  // namespace

SceneInfo hex_lattice_scene() {
    return {"hex_lattice", read_hex_lattice, {}};
}

}  // namespace scenes
