// Phyllotaxis ("Plants hidden in mathematical formulas", 2017, part 2): the
// article's drawPhy(240, 137.508, 3, 7, 200) sunflower, seeds as outlined
// discs in the article's colours and rhombus petals from seed 200 on, beside
// the same spiral at divergences that miss the golden angle.
#include <cmath>

#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "figures/step_runner.hpp"
#include "render/layout.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "sim/check.hpp"
#include "sim/phyllotaxis.hpp"

namespace figures {
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

}  // namespace

void render_phyllotaxis(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"seeds", "seeds placed (the article's t)"},
                     {"divergences", "divergence angle of each panel, degrees"},
                     {"spacing", "radius factor d: seed n at d sqrt(n)"},
                     {"petal_start", "seeds from this one on are drawn as petals"},
                     {"seed_radius", "seed disc radius in the article's turtle units"},
                     {"petal_size", "petal side in turtle units"}});
    Settings style("style", d.style, {{"line_width", "outline width in pixels at scale 1"}});
    std::vector<sim::PhyllotaxisParams> flowers;
    FlowerStyle look;
    try {
        const int seeds = params.count("seeds", 240);
        const double spacing = params.number("spacing", 7);
        for (double divergence : params.numbers("divergences", {137.508, 137.3, 137.6})) {
            flowers.push_back({seeds, divergence, spacing});
            flowers.back().validate();
        }
        look.petal_start = params.count("petal_start", 200);
        look.seed_radius = params.number("seed_radius", 10);
        look.petal_size = params.number("petal_size", 60);
        sim::require_number("seed_radius", look.seed_radius, 0.1, 1000);
        sim::require_number("petal_size", look.petal_size, 0.1, 1000);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (flowers.empty()) throw UsageError(d.id + ": params.divergences is empty");
    const float line_width = float(style.number("line_width", 1.0) * options.scale);
    std::vector<std::vector<sim::Seed>> spirals;
    for (const auto& f : flowers) spirals.push_back(sim::vogel_spiral(f));

    // The animation places the first flower's seeds one by one: frame k shows k seeds.
    Description plan = d;
    plan.panels.clear();
    StepRunner run(plan, options, progress);
    render::PanelRowStyle row;
    row.scale = float(options.scale);
    run.run({.check = {},
             .panel = {},
             .frame =
                 [&](int step) {
                     auto& canvas = run.frame_canvas();
                     canvas.clear({1, 1, 1, 1});
                     const auto rects = render::panel_row(canvas.width(), canvas.height(), 1, true, row);
                     render::Shapes shapes;
                     draw_flower(shapes, rects[0], spirals[0], step, flowers[0].divergence, look, line_width);
                     shapes.draw(canvas);
                     const std::string title =
                         format_fixed(flowers[0].divergence, 3) + "\u00b0, " + std::to_string(step) + " seeds";
                     render::Text text;
                     render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
                     text.add(font, title, {rects[0].centre().x, rects[0].y - row.title_pad * row.scale}, {0, 0, 0, 1},
                              render::Align::centre, render::Baseline::baseline);
                     text.draw(canvas);
                     return canvas.read();
                 },
             .advance = [] { return true; }});

    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    const auto rects = render::panel_row(width, height, int(flowers.size()), true, row);
    render::Shapes shapes;
    std::vector<std::string> titles;
    nlohmann::json panel_meta = nlohmann::json::array();
    for (std::size_t i = 0; i < flowers.size(); ++i) {
        draw_flower(shapes, rects[i], spirals[i], flowers[i].seeds, flowers[i].divergence, look, line_width);
        titles.push_back(format_fixed(flowers[i].divergence, 3) + "\u00b0");
        panel_meta.push_back({{"divergence_degrees", flowers[i].divergence},
                              {"seeds", flowers[i].seeds},
                              {"petals", std::max(0, flowers[i].seeds - look.petal_start)},
                              {"outer_radius", flowers[i].spacing * std::sqrt(double(flowers[i].seeds - 1))},
                              {"state_sha256", seeds_hash(spirals[i])}});
    }
    shapes.draw(canvas);
    // Titles only: the flowers have no frames.
    render::Text text;
    render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
    for (std::size_t i = 0; i < rects.size(); ++i)
        text.add(font, titles[i], {rects[i].centre().x, rects[i].y - row.title_pad * row.scale}, {0, 0, 0, 1},
                 render::Align::centre, render::Baseline::baseline);
    text.draw(canvas);
    run.write_figure(canvas.read(), {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}});
}

}  // namespace figures
