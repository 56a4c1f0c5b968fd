// A 3-D bracketed L-system plant ("Plants hidden in mathematical formulas",
// part 1, "even three-dimensional plants"): the ABOP turtle's segments drawn
// as lit, shaded tubes in perspective, and a turntable film.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/layout.hpp"
#include "render/text.hpp"
#include "render/tubes.hpp"
#include "scenes/field_stats.hpp"
#include "scenes/model_check.hpp"
#include "scenes/plot_page.hpp"
#include "scenes/scene.hpp"
#include "scenes/step_runner.hpp"
#include "scenes/figure_caption.hpp"
#include "sim/check.hpp"
#include "sim/lsystem.hpp"
#include "sim/turtle.hpp"

namespace scenes {
namespace {

const std::vector<Key> param_keys = {
    {"axiom", "the depth-0 string"},
    {"rules", "rewriting rules"},
    {"rule", "a single rule, replacing rules"},
    {"depth", "rewriting depth"},
    {"angle", "every turn, pitch and roll, degrees"},
    {"length", "segment length"},
    {"width", "trunk width"},
    {"width_decay", "factor of '!'"},
};

const std::vector<Key> style_keys = {
    {"bark_colour", "colour at the trunk"},       {"leaf_colour", "colour of the thinnest twigs"},
    {"views", "azimuths of the panels, degrees"}, {"elevation", "camera elevation, degrees"},
    {"sides", "facets around each tube"},
};

constexpr int max_depth = 64;                  // far past any budget: the counts are cheap, the drawing is not
constexpr int min_sides = 3, max_sides = 256;  // what render::draw_tubes draws
constexpr double max_azimuth = 360;            // degrees either way: one turn
constexpr double max_elevation = 90;           // degrees: straight down or up; beyond, the camera turns over
// The panels' width / height follows the plant's box within these.
constexpr float min_aspect = 0.5f, max_aspect = 2.0f;

// A plant without a segment has nothing to frame; the turtle refuses one
// over its segment budget when it starts drawing (sim/turtle.cpp): both
// refused here, in phase 1.
void require_drawn_segments(Settings& params, int depth, std::uint64_t segments, std::uint64_t budget) {
    if (segments == 0) params.refuse("depth", "a depth at which the plant draws a segment (an 'F'); it draws none");
    check_model(params, [&] { sim::require_segment_budget(depth, segments, budget); });
}

// The axiom and rules, a single "rule" replacing the list; the parser's
// messages name the key that gave each rule.
sim::LSystem read_system(Settings& params) {
    std::vector<std::string> rules = params.texts("rules", {});
    const bool single = params.has("rule");
    if (single) rules = {params.text("rule", "")};
    const std::string axiom = params.text("axiom", "A");
    KeyNames names;
    for (std::size_t i = 0; i < rules.size(); ++i) {
        const std::string model_name = "rules[" + std::to_string(i) + "]";
        names.push_back({model_name, single ? "rule" : model_name});
    }
    sim::LSystem system;
    check_model(
        params, [&] { system = sim::LSystem::parse(axiom, rules); }, names);
    return system;
}

sim::Turtle3Params read_turtle(Settings& params) {
    sim::Turtle3Params turtle;
    turtle.angle_degrees = params.number("angle", 22.5);
    turtle.length = params.number("length", 1);
    turtle.width = params.number("width", 0.1);
    turtle.width_decay = params.number("width_decay", 0.7);
    check_model(params, [&] { turtle.validate(); }, {{"angle_degrees", "angle"}});
    return turtle;
}

// Whether `count` panels in a row of the figure are each a pixel at least
// both ways, for any box the plant may have: the narrowest panels come with
// the least aspect, the flattest with the greatest.
bool views_fit(int count, int width, int height, float scale) {
    render::PanelRowStyle row;
    row.scale = scale;
    for (const float aspect : {min_aspect, max_aspect}) {
        row.aspect = aspect;
        for (const render::Rect& r : render::panel_row(width, height, count, true, row))
            if (r.w < 1 || r.h < 1) return false;
    }
    return true;
}

// The panels' azimuths: each within a turn either way, and no more panels than the figure has pixels for.
std::vector<double> read_views(Settings& style, int width, int height, float scale) {
    const auto views = style.numbers("views", {30, 150});
    const std::string each =
        "azimuths in degrees, each from " + sim::shown(-max_azimuth) + " to " + sim::shown(max_azimuth);
    for (const double azimuth : views)
        if (!(std::abs(azimuth) <= max_azimuth)) style.refuse("views", sim::shown(azimuth), each);
    if (views.empty() || !views_fit(int(views.size()), width, height, scale)) {
        int most = 0;
        while (most < width && views_fit(most + 1, width, height, scale)) ++most;
        style.refuse("views", std::to_string(views.size()) + " azimuths",
                     "1 to " + std::to_string(most) + " " + each + " (the figure's panels a pixel at least)");
    }
    return views;
}

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

// The tubes and the box that holds them.
struct Plant {
    std::vector<render::Tube> tubes;
    glm::vec3 lo, hi;
};

// The renderer takes the tubes as floats and the camera frames their box
// with squared distances, which overflow near 1e19 units: past that the
// picture goes blank (and past 3e38 a tube is infinite) long before the
// turtle's doubles fail. Like the turtle's own health check, only the run
// can tell, the widths and lengths compounding over the string.
void require_framable(const Plant& plant) {
    constexpr double most = 1e15;
    const double size = glm::length(glm::dvec3(plant.hi) - glm::dvec3(plant.lo));
    if (!(size <= most))
        throw std::runtime_error("the plant is " + sim::shown(size) + " units across, more than the renderer frames (" +
                                 sim::shown(most) + "); no image written");
}

class LSystem3dScene : public SceneBase {
public:
    LSystem3dScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_keys, style_keys),
          system_(read_system(params_)),
          depth_(params_.count_in("depth", 7, 0, max_depth)),
          turtle_(read_turtle(params_)),
          bark_(style_colour(style_, "bark_colour", "#6b4a2b")),
          leaf_(style_colour(style_, "leaf_colour", "#3c8d2f")),
          views_(read_views(style_, figure_width(d, options), figure_height(d, options),
                            float(options.scale))),
          elevation_(float(style_.number_in("elevation", 12, -max_elevation, max_elevation))),
          sides_(style_.count_in("sides", 12, min_sides, max_sides)),
          segments_(sim::segment_count(system_, depth_, false)) {
        require_drawn_segments(params_, depth_, segments_, turtle_.segment_budget);
    }

    // Each segment: the turtle's Segment3, its 8 doubles hashed, its tube
    // here and in llvmpipe's instance buffer (one capsule mesh serves them
    // all); and llvmpipe's queue of binned triangles. Measured at depths 8
    // to 11 (up to 318,552 segments): 1.0 to 1.5 times below this.
    std::vector<MemoryNeed> memory() const override {
        return {{"plant of depth " + std::to_string(depth_) + ", " + std::to_string(segments_) + " segments",
                 static_cast<double>(segments_) *
                     (sizeof(sim::Segment3) + 8 * sizeof(double) + 2.0 * sizeof(render::Tube))},
                {"llvmpipe's queue of binned triangles", render::queued_triangles_bytes},
                {"depth samples of the figure and film canvases", depth_bytes()}};
    }

    // The 3-D canvases' 4x multisampled depth buffers (24-bit depth with its
    // stencil byte: 16 bytes a pixel), beyond what the estimate counts for a
    // 2-D canvas.
    double depth_bytes() const {
        double pixels = double(figure_width(d_, options_)) * figure_height(d_, options_);
        if (d_.animation && options_.film)
            pixels += double(scaled_even(d_.animation->width, options_.scale)) *
                      scaled_even(d_.animation->height, options_.scale);
        return 16.0 * pixels;
    }

    void render(Output& out) const override {
        const std::vector<sim::Segment3> segments = sim::interpret_3d(system_, depth_, turtle_);
        Plant plant;
        plant.tubes = tubes_of(segments, turtle_.width, bark_, leaf_);
        // Named copies, not a structured binding: clang 14 (make fuzz) cannot capture those in a lambda.
        const auto bounds_of_tubes = render::tube_bounds(plant.tubes);
        plant.lo = bounds_of_tubes.first;
        plant.hi = bounds_of_tubes.second;
        require_framable(plant);

        // The turntable: one turn around the vertical axis over the film.
        Description plan = d_;
        plan.panels.clear();
        StepRunner run(plan, options_, out);
        render::PanelRowStyle row;
        row.scale = float(options_.scale);
        render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
        run.run({.check = {},
                 .panel = {},
                 .frame = [&](int step) { return turntable_frame(run.frame_canvas(true), plant, step); },
                 .advance = [] { return true; }});

        if (run.film_only()) return run.finish_film();  // a film segment's run: no figure
        nlohmann::json panel_meta = nlohmann::json::array();
        for (double azimuth : views_)
            panel_meta.push_back({{"azimuth_degrees", azimuth}, {"elevation_degrees", elevation_}});
        const FigureDrawing figure{figure_width(d_, options_), figure_height(d_, options_), true,
                                   [&](render::Surface& surface) { draw_views(surface, plant, row, font); }};
        const glm::vec3 lo = plant.lo, hi = plant.hi;
        run.write_figure(figure, {{"params", params_.used()},
                                  {"style", style_.used()},
                                  {"panels", panel_meta},
                                  {"segments", segments.size()},
                                  {"state_sha256", segments_hash(segments)},
                                  {"symbols", system_.length(depth_)},
                                  {"bounds", {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}}});
    }

private:
    // The film's frame at `step`: the plant seen from its share of one turn.
    render::Image turntable_frame(render::Canvas& canvas, const Plant& plant, int step) const {
        canvas.clear({1, 1, 1, 1});
        const render::Rect view{0, 0, float(canvas.width()), float(canvas.height())};
        const float azimuth = 360.0f * float(step) / float(d_.animation->last + 1);
        render::draw_tubes(canvas, view, plant.tubes,
                           render::frame_bounds(plant.lo, plant.hi, azimuth, elevation_, view.w / view.h), {}, sides_);
        return canvas.read();
    }

    // The figure: one panel per azimuth, titled.
    void draw_views(render::Surface& canvas, const Plant& plant, render::PanelRowStyle row, render::Font& font) const {
        const int width = canvas.width(), height = canvas.height();
        canvas.background({1, 1, 1, 1});
        const glm::vec3 lo = plant.lo, hi = plant.hi;
        row.aspect = float(std::clamp((hi.x - lo.x) / std::max(1e-6f, hi.y - lo.y), min_aspect, max_aspect));
        const auto rects = render::panel_row(width, height, int(views_.size()), true, row);
        render::Text text;
        for (std::size_t i = 0; i < views_.size(); ++i) {
            render::draw_tubes(canvas, rects[i], plant.tubes,
                               render::frame_bounds(lo, hi, float(views_[i]), elevation_, rects[i].w / rects[i].h), {},
                               sides_);
            const std::string title = "azimuth " + format_fixed(views_[i], 0) + "\u00b0";
            text.add(font, title, {rects[i].centre().x, rects[i].y - row.title_pad * row.scale}, {0, 0, 0, 1},
                     render::Align::centre, render::Baseline::baseline);
        }
        text.draw(canvas);
    }

    const sim::LSystem system_;
    const int depth_;
    const sim::Turtle3Params turtle_;
    const glm::vec4 bark_, leaf_;
    const std::vector<double> views_;  // azimuths, degrees
    const float elevation_;            // degrees
    const int sides_;
    const std::uint64_t segments_;  // what the turtle will draw, counted without drawing
};

}  // namespace

std::unique_ptr<Scene> read_lsystem_3d(const Description& d, const SceneOptions& options) {
    return std::make_unique<LSystem3dScene>(d, options);
}

}  // namespace scenes
