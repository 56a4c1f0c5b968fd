// A 3-D bracketed L-system plant ("Plants hidden in mathematical formulas",
// part 1, "even three-dimensional plants"): the ABOP turtle's segments drawn
// as lit, shaded tubes in perspective, and a turntable film.
#include <cmath>

#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "figures/step_runner.hpp"
#include "render/layout.hpp"
#include "render/text.hpp"
#include "render/tubes.hpp"
#include "sim/check.hpp"
#include "sim/lsystem.hpp"
#include "sim/turtle.hpp"

namespace figures {
namespace {

// Bark at the trunk to green at the thinnest twigs, by the segment's width.
std::vector<render::Tube> tubes_of(const std::vector<sim::Segment3>& segments, double trunk_width,
                                   const glm::vec4& bark, const glm::vec4& leaf) {
    std::vector<render::Tube> tubes;
    tubes.reserve(segments.size());
    for (const auto& s : segments) {
        const float t = float(std::clamp(1.0 - s.width / trunk_width, 0.0, 1.0));
        const glm::vec4 colour = glm::mix(bark, leaf, std::sqrt(t));
        const float r = float(s.width / 2);
        tubes.push_back({glm::vec3(s.a), glm::vec3(s.b), r, r, colour});
    }
    return tubes;
}

// SHA-256 of the turtle's segments in drawing order: from, to, width, level.
std::string segments_hash(const std::vector<sim::Segment3>& segments) {
    std::vector<double> values;
    values.reserve(8 * segments.size());
    for (const auto& s : segments)
        values.insert(values.end(), {s.a.x, s.a.y, s.a.z, s.b.x, s.b.y, s.b.z, s.width, double(s.level)});
    return state_hash(values);
}

}  // namespace

void render_lsystem_3d(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"axiom", "the depth-0 string"},
                     {"rules", "rewriting rules"},
                     {"rule", "a single rule, replacing rules"},
                     {"depth", "rewriting depth"},
                     {"angle", "every turn, pitch and roll, degrees"},
                     {"length", "segment length"},
                     {"width", "trunk width"},
                     {"width_decay", "factor of '!'"}});
    Settings style("style", d.style,
                   {{"bark_colour", "colour at the trunk"},
                    {"leaf_colour", "colour of the thinnest twigs"},
                    {"views", "azimuths of the panels, degrees"},
                    {"elevation", "camera elevation, degrees"},
                    {"sides", "facets around each tube"}});
    sim::LSystem system;
    sim::Turtle3Params turtle;
    int depth = 0;
    try {
        std::vector<std::string> rules = params.texts("rules", {});
        if (params.has("rule")) rules = {params.text("rule", "")};
        system = sim::LSystem::parse(params.text("axiom", "A"), rules);
        depth = params.count("depth", 7);
        sim::require_integer("depth", depth, 0, 64);
        turtle.angle_degrees = params.number("angle", 22.5);
        turtle.length = params.number("length", 1);
        turtle.width = params.number("width", 0.1);
        turtle.width_decay = params.number("width_decay", 0.7);
        turtle.validate();
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const glm::vec4 bark = style_colour(style, "bark_colour", "#6b4a2b");
    const glm::vec4 leaf = style_colour(style, "leaf_colour", "#3c8d2f");
    const auto views = style.numbers("views", {30, 150});
    const float elevation = float(style.number("elevation", 12));
    const int sides = style.count("sides", 12);
    if (views.empty()) throw UsageError(d.id + ": style.views is empty");

    // Each segment: the turtle's, its tube and the tube's mesh (two rings of
    // `sides` vertices, position and normal as floats, and 6 * sides indices).
    require_memory(d, options,
                   {{"plant of depth " + std::to_string(depth),
                     static_cast<double>(sim::segment_count(system, depth, false)) *
                         (sizeof(sim::Segment3) + sizeof(render::Tube) + 2.0 * sides * 6 * sizeof(float) +
                          6.0 * sides * sizeof(std::uint32_t))}});
    std::vector<sim::Segment3> segments;
    try {
        segments = sim::interpret_3d(system, depth, turtle);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (segments.empty()) throw UsageError(d.id + ": the plant draws no segment at this depth");
    const auto tubes = tubes_of(segments, turtle.width, bark, leaf);
    // Named copies, not a structured binding: clang 14 (make fuzz) cannot capture those in a lambda.
    const auto bounds_of_tubes = render::tube_bounds(tubes);
    const auto lo = bounds_of_tubes.first, hi = bounds_of_tubes.second;

    // The turntable: one turn around the vertical axis over the film.
    Description plan = d;
    plan.panels.clear();
    StepRunner run(plan, options, progress);
    render::PanelRowStyle row;
    row.scale = float(options.scale);
    render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
    run.run({.check = {},
             .panel = {},
             .frame =
                 [&](int step) {
                     auto& canvas = run.frame_canvas(true);
                     canvas.clear({1, 1, 1, 1});
                     const render::Rect view{0, 0, float(canvas.width()), float(canvas.height())};
                     const float azimuth = 360.0f * float(step) / float(d.animation->last + 1);
                     render::draw_tubes(canvas, view, tubes,
                                        render::frame_bounds(lo, hi, azimuth, elevation, view.w / view.h), {}, sides);
                     return canvas.read();
                 },
             .advance = [] { return true; }});

    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height, 4, true);
    canvas.clear({1, 1, 1, 1});
    row.aspect = float(std::clamp((hi.x - lo.x) / std::max(1e-6f, hi.y - lo.y), 0.5f, 2.0f));
    const auto rects = render::panel_row(width, height, int(views.size()), true, row);
    render::Text text;
    nlohmann::json panel_meta = nlohmann::json::array();
    for (std::size_t i = 0; i < views.size(); ++i) {
        render::draw_tubes(canvas, rects[i], tubes,
                           render::frame_bounds(lo, hi, float(views[i]), elevation, rects[i].w / rects[i].h), {},
                           sides);
        const std::string title = "azimuth " + format_fixed(views[i], 0) + "\u00b0";
        text.add(font, title, {rects[i].centre().x, rects[i].y - row.title_pad * row.scale}, {0, 0, 0, 1},
                 render::Align::centre, render::Baseline::baseline);
        panel_meta.push_back({{"azimuth_degrees", views[i]}, {"elevation_degrees", elevation}});
    }
    text.draw(canvas);
    run.write_figure(canvas.read(), {{"params", params.used()},
                                     {"style", style.used()},
                                     {"panels", panel_meta},
                                     {"segments", segments.size()},
                                     {"state_sha256", segments_hash(segments)},
                                     {"symbols", system.length(depth)},
                                     {"bounds", {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}}});
}

}  // namespace figures
