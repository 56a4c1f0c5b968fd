// Phyllotaxis ("Plants hidden in mathematical formulas", 2017, part 2): the
// article's drawPhy(240, 137.508, 3, 7, 200) sunflower, seeds as outlined
// discs in the article's colours and rhombus petals from seed 200 on, beside
// the same spiral at divergences that miss the golden angle.
#include <cmath>

#include "render/layout.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/phyllotaxis.hpp"

namespace scenes {
namespace {

struct FlowerStyle {
    int petal_start = 200;    // seeds from this one on are drawn as petals
    double seed_radius = 10;  // the turtle's circle stamp: 20 units across
    double petal_size = 60;   // side of a petal rhombus
    double window = 500;      // the article's 500 x 500 turtle window, mapped onto a panel
};

// The article's seed colour: (255, theta % 255, 4n % 255) in 0..255, theta in radians.
glm::vec4 seed_colour(const sim::Seed& s) {
    return {1.0f, float(int(std::fmod(s.angle, 255.0))) / 255.0f, float((s.n * 4) % 255) / 255.0f, 1.0f};
}

// Draws the first `count` seeds of `seeds` into `panel`.
void draw_flower(render::Shapes& shapes, const render::Rect& panel, const std::vector<sim::Seed>& seeds, int count,
                 double divergence, const FlowerStyle& style, float line_width) {
    const float scale = float(std::min(panel.w, panel.h) / style.window);
    const glm::vec2 centre = panel.centre();
    auto to_pixels = [&](glm::dvec2 p) { return centre + scale * glm::vec2(float(p.x), -float(p.y)); };
    const glm::vec4 black{0, 0, 0, 1}, yellow{1, 1, 0, 1};
    for (int i = 0; i < count && i < int(seeds.size()); ++i) {
        const sim::Seed& s = seeds[i];
        if (s.n >= style.petal_start) {
            // The article's petal: heading n * angle, then rt 20, fd, lt 40, fd, lt 140, fd, lt 40, fd.
            const double h = s.n * divergence;
            auto step = [&](glm::dvec2 from, double degrees) {
                const double a = degrees * M_PI / 180.0;
                return from + style.petal_size * glm::dvec2(std::cos(a), std::sin(a));
            };
            const glm::dvec2 p0 = s.position, p1 = step(p0, h - 20), p2 = step(p1, h + 20), p3 = step(p2, h + 160);
            const glm::vec2 corners[5] = {to_pixels(p0), to_pixels(p1), to_pixels(p2), to_pixels(p3), to_pixels(p0)};
            shapes.convex_polygon(std::span(corners, 4), yellow);
            shapes.polyline(corners, line_width, black);
        } else {
            const glm::vec2 c = to_pixels(s.position);
            const float r = float(style.seed_radius) * scale;
            shapes.disc(c, r, seed_colour(s));
            shapes.ring(c, r - line_width / 2, r + line_width / 2, black);
        }
    }
}

// SHA-256 of the seeds in placement order: n, x, y, angle.
std::string seeds_hash(const std::vector<sim::Seed>& seeds) {
    std::vector<double> values;
    values.reserve(4 * seeds.size());
    for (const auto& s : seeds) values.insert(values.end(), {double(s.n), s.position.x, s.position.y, s.angle});
    return state_hash(values);
}

struct Params {
    // At most what --max-memory 4G serves for the default three flowers at the
    // figure's size (50,000 seeds: 2.0 GiB; the model's 100,000 would need 4.1).
    int seeds = 240;
    std::vector<double> divergences{137.508, 137.3, 137.6};
    double spacing = 7;
    FlowerStyle look;
    std::vector<sim::PhyllotaxisParams> flowers;  // one per divergence, all with the same seeds and spacing
};

const Schema<Params> param_schema = [] {
    Schema<FlowerStyle> look;
    look.count("petal_start", &FlowerStyle::petal_start, "seeds from this one on are drawn as petals", 0, 100000);
    look.number("seed_radius", &FlowerStyle::seed_radius, "seed disc radius in the article's turtle units", 0.1, 1000);
    look.number("petal_size", &FlowerStyle::petal_size, "petal side in turtle units", 0.1, 1000);
    Schema<Params> s;
    s.count("seeds", &Params::seeds, "seeds placed (the article's t)", 1, 50000);
    s.key(
        {"divergences", "divergence angle of each panel, degrees", "a list of numbers"},
        [](Settings& section, const std::string& key, Params& p) {
            p.divergences = section.numbers(key, p.divergences);
            if (p.divergences.empty()) section.refuse(key, "one divergence angle at least, in degrees");
        },
        [](const Params& d) { return nlohmann::json(d.divergences); });
    s.number("spacing", &Params::spacing, "radius factor d: seed n at d sqrt(n)");
    s.part(look, &Params::look);
    s.check([](Settings& section, const std::string&, Params& p) {
        for (std::size_t i = 0; i < p.divergences.size(); ++i) {
            p.flowers.push_back({p.seeds, p.divergences[i], p.spacing});
            check_model(section, [&] { p.flowers.back().validate(); },
                        {{"divergence", "divergences[" + std::to_string(i) + "]"}});
        }
    });
    return s;
}();

struct Style {
    double line_width = 1.0;
};
const Schema<Style> style_schema =
    Schema<Style>().number("line_width", &Style::line_width, "outline width in pixels at scale 1", 0.0, 20.0);

render::PanelRowStyle row_style(double scale) {
    render::PanelRowStyle row;
    row.scale = float(scale);
    return row;
}

class PhyllotaxisScene : public SceneBase {
public:
    PhyllotaxisScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          line_width_(float(style_schema.read(style_).line_width * options.scale)),
          row_(row_style(options.scale)) {
        refuse_steps(d, "each panel shows a whole flower (the film places the seeds one a step)", false);
        require_text_fits(d, options, [&](const render::Rect& area) { return render::page_text(figure_layout(area)); });
    }

    void render(Output& out) const override {
        std::vector<std::vector<sim::Seed>> spirals;
        for (const auto& f : p_.flowers) spirals.push_back(sim::vogel_spiral(f));
        // The animation places the first flower's seeds one by one: frame k shows k seeds.
        StepRunner run(d_, options_, out);
        run.run({.check = {},
                 .panel = {},
                 .frame =
                     [&](int step) {
                         return FrameDrawing{[&, step](render::Surface& surface) { draw_frame(surface, spirals[0], step); }};
                     },
                 .advance = [] { return true; }});
        if (run.film_only()) return run.finish_film();  // a film segment's run: no figure
        nlohmann::json panel_meta = nlohmann::json::array();
        Page page;
        add_figure(page, spirals, panel_meta);
        const FigureDrawing figure{figure_width(d_, options_), figure_height(d_, options_), false,
                                   [&page](render::Surface& surface) {
                                       surface.background({1, 1, 1, 1});
                                       page.shapes.draw(surface);
                                       page.text.draw(surface);
                                   }};
        run.write_figure(figure, {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
    }

    // Each flower's seeds, and its discs, rings and petals as triangles, in
    // the batch and again in llvmpipe's copy of it (the batch's growth
    // touches no more: a doubling copy is the same twice). The figure draws
    // every flower; a frame only the first, so the figure bounds it too.
    std::vector<MemoryNeed> memory() const override {
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        int most = std::min(width, height);
        if (d_.animation && options_.film)
            most = std::max(most, std::min(scaled_even(d_.animation->width, options_.scale),
                                           scaled_even(d_.animation->height, options_.scale)));
        // A seed's disc and outline ring at their largest (a panel the figure's
        // size); a petal's two triangles and its outline of four segments, each
        // joint at most a bevel and a fan of 12.
        const float radius = float(p_.look.seed_radius * most / p_.look.window);
        const double seed = double(render::Shapes::disc_vertices(radius) +
                                   2 * render::Shapes::disc_vertices(radius + line_width_ / 2));
        const double petal = 6.0 + 4 * 6.0 + 3 * (6.0 + render::Shapes::min_disc_vertices);
        // What Shapes records: a seed's disc and ring (an op and a point
        // each), a petal's polygon and outline (an op and 4 or 5 points each).
        constexpr double op = sizeof(render::Shapes::Op), point = sizeof(glm::vec2);
        const double seed_ops = 2 * (op + point), petal_ops = 2 * op + 9 * point;
        double vertices = 0, seeds = 0, recorded = 0;
        for (const auto& f : p_.flowers) {
            const double discs = std::min(f.seeds, p_.look.petal_start);
            vertices += discs * seed + (f.seeds - discs) * petal;
            recorded += discs * seed_ops + (f.seeds - discs) * petal_ops;
            seeds += f.seeds;
        }
        // The seeds and their hash's doubles, and what Shapes records, each
        // up to twice its size while it grows; and one batch of triangles as
        // drawn (at most triangles_per_finish) four times over: figgen's
        // buffer up to twice its size while it grows, and llvmpipe's copy,
        // which with these large fans measured tighter than the plants'.
        // Peak RSS against this estimate: 237 MiB / 295 for 50,000 seeds as
        // discs (with twice over, 242: too close), 196 / 283 for 30,000
        // petals, 215 / 384 for the catalog figure with its film.
        return {
            {std::to_string(p_.flowers.size()) + " flowers of " + std::to_string(p_.flowers.front().seeds) + " seeds",
             2.0 * (seeds * (sizeof(sim::Seed) + 4 * sizeof(double)) + recorded) +
                 4.0 * render::Shapes::bytes_per_vertex *
                     std::min(vertices, 3.0 * static_cast<double>(render::triangles_per_finish))}};
    }

private:
    // A title above a panel, in the panel row's title font.
    void add_title(render::Text& text, const render::Rect& rect, const std::string& title) const {
        render::Font& font = render::font_of_size(std::round(row_.title_size * row_.scale));
        text.add(font, title, {rect.centre().x, rect.y - row_.title_pad * row_.scale}, {0, 0, 0, 1},
                 render::Align::centre, render::Baseline::baseline);
    }

    void draw_frame(render::Surface& canvas, const std::vector<sim::Seed>& spiral, int step) const {
        canvas.background({1, 1, 1, 1});
        const auto rects = render::panel_row(canvas.width(), canvas.height(), 1, true, row_);
        render::Shapes shapes;
        draw_flower(shapes, rects[0], spiral, step, p_.flowers[0].divergence, p_.look, line_width_);
        shapes.draw(canvas);
        render::Text text;
        add_title(text, rects[0],
                  format_fixed(p_.flowers[0].divergence, 3) + "\u00b0, " + std::to_string(step) + " seeds");
        text.draw(canvas);
    }

    struct Page {
        render::Shapes shapes;
        render::Text text;
    };

    // Each flower's title: its divergence angle.
    std::vector<std::string> titles() const {
        std::vector<std::string> titles;
        for (const sim::PhyllotaxisParams& f : p_.flowers) titles.push_back(format_fixed(f.divergence, 3) + "\u00b0");
        return titles;
    }

    // The flowers' panels in `area`, in the grid chosen for it, and their titles.
    render::GridText figure_layout(const render::Rect& area) const {
        return titled_grid_text(area, titles(), figure_columns(d_, area, int(p_.flowers.size()), true, row_), true,
                                row_);
    }

    // Every flower whole, a panel each, into `page`; their metadata into `panel_meta`.
    void add_figure(Page& page, const std::vector<std::vector<sim::Seed>>& spirals, nlohmann::json& panel_meta) const {
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        const std::vector<render::Rect> rects = figure_layout({0, 0, float(width), float(height)}).panels;
        render::Shapes& shapes = page.shapes;
        const std::vector<std::string> titles = this->titles();
        for (std::size_t i = 0; i < p_.flowers.size(); ++i) {
            const sim::PhyllotaxisParams& f = p_.flowers[i];
            draw_flower(shapes, rects[i], spirals[i], f.seeds, f.divergence, p_.look, line_width_);
            panel_meta.push_back({{"divergence_degrees", f.divergence},
                                  {"seeds", f.seeds},
                                  {"petals", std::max(0, f.seeds - p_.look.petal_start)},
                                  {"outer_radius", f.spacing * std::sqrt(double(f.seeds - 1))},
                                  {"state_sha256", seeds_hash(spirals[i])}});
        }
        // Titles only: the flowers have no frames.
        for (std::size_t i = 0; i < rects.size(); ++i) add_title(page.text, rects[i], titles[i]);
    }

    const Params p_;
    const float line_width_;           // pixels, scaled
    const render::PanelRowStyle row_;  // the panels' layout and title font
};

std::unique_ptr<Scene> read_phyllotaxis(const Description& d, const SceneOptions& options) {
    return std::make_unique<PhyllotaxisScene>(d, options);
}

}  // namespace

SceneInfo phyllotaxis_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"phyllotaxis",
            read_phyllotaxis,
            {},
            {
                {"/panels/*/divergence_degrees",
                 "divergence angle, panel {#}",
                 "number",
                 "degrees",
                 {{"", "137.508 (the golden angle)"}},
                 "",
                 "",
                 6},
                {"/panels/*/seeds", "seeds, panel {#}", "integer", ""},
            }};
}

}  // namespace scenes
