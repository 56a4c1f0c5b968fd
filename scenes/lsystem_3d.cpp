// A 3-D bracketed L-system plant ("Plants hidden in mathematical formulas",
// part 1, "even three-dimensional plants"): the ABOP turtle's segments drawn
// as lit, shaded tubes and its polygons (leaves) as lit facets in one
// depth-tested perspective picture, framed so the plant fills its panels,
// and a turntable film.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/layout.hpp"
#include "render/text.hpp"
#include "render/tubes.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"
#include "sim/check.hpp"
#include "sim/lsystem.hpp"
#include "sim/turtle.hpp"

namespace scenes {
namespace {

constexpr int max_depth = 64;                  // far past any budget: the counts are cheap, the drawing is not
constexpr int min_sides = 3, max_sides = 256;  // what render::draw_tubes draws
constexpr double max_azimuth = 360;            // degrees either way: one turn
constexpr double max_elevation = 90;           // degrees: straight down or up; beyond, the camera turns over
constexpr int max_leaf_index = 1 << 20;        // far past any colour table
// The panels' width / height follows the plant's box within these.
constexpr float min_aspect = 0.5f, max_aspect = 2.0f;

// A plant without a segment has nothing to frame; the turtle refuses one
// over its segment or vertex budget when it starts drawing
// (sim/turtle.cpp): all refused here, in phase 1.
void require_drawn_segments(Settings& params, int depth, std::uint64_t segments, std::uint64_t vertices,
                            const sim::Turtle3Params& turtle) {
    if (segments == 0) params.refuse("depth", "a depth at which the plant draws a segment (an 'F'); it draws none");
    check_model(params, [&] { sim::require_segment_budget(depth, segments, turtle.segment_budget); });
    check_model(params, [&] { sim::require_vertex_budget(depth, vertices, turtle.vertex_budget); });
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
// ABOP's colour table, made of two colours: index 0 is bark, leaf_index and
// above leaf, the indices between a mix (each ' a step from bark to leaf).
struct Palette {
    glm::vec4 bark, leaf;
    int leaf_index;  // >= 1
    glm::vec4 operator()(int index) const {
        return glm::mix(bark, leaf, float(std::min(index, leaf_index)) / float(leaf_index));
    }
};

// Each segment a tube as wide as the pen, in its colour index's colour.
std::vector<render::Tube> tubes_of(const std::vector<sim::Segment3>& segments, const Palette& palette) {
    std::vector<render::Tube> tubes;
    tubes.reserve(segments.size());
    for (const auto& s : segments) {
        const float r = float(s.width / 2);
        tubes.push_back({glm::vec3(s.a), glm::vec3(s.b), r, r, palette(s.colour)});
    }
    return tubes;
}

// Each polygon a fan of facets from its first vertex: right for the convex,
// nearly planar leaves of ABOP (Fig 1.25's are flat hexagons).
std::vector<render::Facet> facets_of(const sim::Drawing3& drawing, const Palette& palette) {
    std::vector<render::Facet> facets;
    facets.reserve(drawing.vertices.size());  // count - 2 a polygon
    for (const sim::Polygon3& polygon : drawing.polygons) {
        const glm::vec4 colour = palette(polygon.colour);
        const auto* v = &drawing.vertices[polygon.first];
        for (std::uint32_t k = 1; k + 1 < polygon.count; ++k)
            facets.push_back({glm::vec3(v[0]), glm::vec3(v[k]), glm::vec3(v[k + 1]), colour});
    }
    return facets;
}

// SHA-256 of what the turtle drew: each segment (from, to, width, level,
// colour) in drawing order, then each polygon (colour, vertex count,
// vertices) in the order they ended.
std::string drawing_hash(const sim::Drawing3& drawing) {
    std::vector<double> values;
    values.reserve(9 * drawing.segments.size() + 2 * drawing.polygons.size() + 3 * drawing.vertices.size());
    for (const auto& s : drawing.segments)
        values.insert(values.end(),
                      {s.a.x, s.a.y, s.a.z, s.b.x, s.b.y, s.b.z, s.width, double(s.level), double(s.colour)});
    for (const auto& p : drawing.polygons) {
        values.insert(values.end(), {double(p.colour), double(p.count)});
        for (std::uint32_t k = 0; k < p.count; ++k) {
            const glm::dvec3& v = drawing.vertices[p.first + k];
            values.insert(values.end(), {v.x, v.y, v.z});
        }
    }
    return state_hash(values);
}

// The tubes, the facets, the balls that frame them and the box that holds them.
struct Plant {
    std::vector<render::Tube> tubes;
    std::vector<render::Facet> facets;
    std::vector<render::Ball> balls;
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

// The default light (from the upper left, in front) carried round with the
// camera: every view and every frame of the turntable lit alike, as on a
// turntable under a studio light, rather than the far side left dark.
render::Light studio_light(const render::Camera& camera) {
    const glm::vec3 back = glm::normalize(camera.eye - camera.target);
    const glm::vec3 right = glm::normalize(glm::cross(camera.up, back)), up = glm::cross(back, right);
    render::Light light;
    const glm::vec3 d = light.direction;  // given for a camera on +z looking down -z
    light.direction = d.x * right + d.y * up + d.z * back;
    return light;
}

struct Params {
    std::string axiom = "A";
    std::vector<std::string> rules;
    int depth = 7;
    sim::Turtle3Params turtle;
    sim::LSystem system;  // the axiom and rules, parsed
};

// The axiom and rules, a single "rule" replacing the list; the parser's
// messages name the key that gave each rule.
const Schema<Params> param_schema = [] {
    using T = sim::Turtle3Params;
    Schema<T> turtle;
    turtle.number("angle", &T::angle_degrees, "every turn, pitch and roll, degrees");
    turtle.number("length", &T::length, "segment length");
    turtle.number("width", &T::width, "trunk width");
    turtle.number("width_decay", &T::width_decay, "factor of '!'");
    turtle.check(validated<T>({{"angle_degrees", "angle"}}));
    Schema<Params> s;
    s.text("axiom", &Params::axiom, "the depth-0 string");
    s.texts("rules", &Params::rules, "rewriting rules");
    s.key({"rule", "a single rule, replacing rules", "text"}, [](Settings& section, const std::string& key, Params& p) {
        if (section.has(key)) p.rules = {section.text(key, "")};
    });
    s.count("depth", &Params::depth, "rewriting depth", 0, max_depth);
    s.part(turtle, &Params::turtle);
    s.check([](Settings& section, const std::string&, Params& p) {
        const bool single = section.has("rule");
        KeyNames names;
        for (std::size_t i = 0; i < p.rules.size(); ++i) {
            const std::string model_name = "rules[" + std::to_string(i) + "]";
            names.push_back({model_name, single ? "rule" : model_name});
        }
        check_model(
            section, [&] { p.system = sim::LSystem::parse(p.axiom, p.rules); }, names);
    });
    return s;
}();

// The figure's size, given before reading: how many views it has pixels for.
struct Style {
    Colour bark = colour("#6b4a2b"), leaf = colour("#3c8d2f");
    int leaf_index = 3;
    std::vector<double> views{30, 150};  // azimuths, degrees
    double elevation = 12;
    int sides = 12;
    int width = 0, height = 0;
    float scale = 1;
};

// The panels' azimuths: each within a turn either way, and no more panels than the figure has pixels for.
void read_views(Settings& style, const std::string& key, Style& s) {
    s.views = style.numbers(key, s.views);
    const std::string each =
        "azimuths in degrees, each from " + sim::shown(-max_azimuth) + " to " + sim::shown(max_azimuth);
    for (const double azimuth : s.views)
        if (!(std::abs(azimuth) <= max_azimuth)) style.refuse(key, sim::shown(azimuth), each);
    if (s.views.empty() || !views_fit(int(s.views.size()), s.width, s.height, s.scale)) {
        int most = 0;
        while (most < s.width && views_fit(most + 1, s.width, s.height, s.scale)) ++most;
        style.refuse(key, std::to_string(s.views.size()) + " azimuths",
                     "1 to " + std::to_string(most) + " " + each + " (the figure's panels a pixel at least)");
    }
}

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"bark_colour", "colour of colour index 0", "a colour"}, &Style::bark, read_colour)
        .field({"leaf_colour", "colour of colour index leaf_index and above", "a colour"}, &Style::leaf, read_colour)
        .count("leaf_index", &Style::leaf_index, "colour index drawn in leaf_colour", 1, max_leaf_index)
        .key({"views", "azimuths of the panels, degrees", "a list of numbers",
              "azimuths from -360 to 360, as many as the figure has pixels for", nlohmann::json({30, 150})},
             read_views)
        .number("elevation", &Style::elevation, "camera elevation, degrees", -max_elevation, max_elevation)
        .count("sides", &Style::sides, "facets around each tube", min_sides, max_sides);

Style sized(const Description& d, const SceneOptions& options) {
    Style s;
    s.width = figure_width(d, options);
    s.height = figure_height(d, options);
    s.scale = float(options.scale);
    return s;
}

// The share of its viewport's height or width the plant fills, whichever it
// reaches first, leaving a margin on the tighter sides.
constexpr float fill = 0.94f;

class LSystem3dScene : public SceneBase {
public:
    LSystem3dScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_, sized(d, options))),
          palette_{s_.bark.rgba, s_.leaf.rgba, s_.leaf_index},
          segments_(sim::segment_count(p_.system, p_.depth, false)),
          vertices_(sim::polygon_vertex_count(p_.system, p_.depth)) {
        require_drawn_segments(params_, p_.depth, segments_, vertices_, p_.turtle);
    }

    // Each segment: the turtle's Segment3, its 9 doubles hashed, its tube
    // here and in llvmpipe's instance buffer (one capsule mesh serves them
    // all), its two framing balls. Each polygon vertex (at most vertices_,
    // a polygon of n giving n - 2 facets): its dvec3 in the drawing and on
    // the turtle's polygon stack, 3 doubles hashed, a facet here, three
    // balls and three corners for GL, each twice (our buffer and llvmpipe's
    // copy). And llvmpipe's queue of binned triangles. Measured at depths 8
    // to 11 (up to 318,552 segments): 1.0 to 1.5 times below this.
    std::vector<MemoryNeed> memory() const override {
        return {
            {"plant of depth " + std::to_string(p_.depth) + ", " + std::to_string(segments_) + " segments",
             static_cast<double>(segments_) * (sizeof(sim::Segment3) + 9 * sizeof(double) + 2.0 * sizeof(render::Tube) +
                                               2.0 * sizeof(render::Ball))},
            {"its polygons, " + std::to_string(vertices_) + " vertices at most",
             static_cast<double>(vertices_) * (2.0 * sizeof(glm::dvec3) + 3 * sizeof(double) + sizeof(render::Facet) +
                                               3.0 * sizeof(render::Ball) + 2.0 * 3 * (10 * sizeof(float)))},
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
        const sim::Drawing3 drawing = sim::interpret_3d(p_.system, p_.depth, p_.turtle);
        Plant plant;
        plant.tubes = tubes_of(drawing.segments, palette_);
        plant.facets = facets_of(drawing, palette_);
        plant.balls = render::balls_of(plant.tubes, plant.facets);
        const auto bounds = sim::bounds(drawing);
        const auto bounds_of_tubes = render::tube_bounds(plant.tubes);  // the radii too
        plant.lo = glm::min(bounds_of_tubes.first, glm::vec3(bounds.lo));
        plant.hi = glm::max(bounds_of_tubes.second, glm::vec3(bounds.hi));
        require_framable(plant);
        // The titles over the panels the plant's shape gives, before the film runs.
        require_text_fits(d_, options_, [&](const render::Rect& area) {
            render::PanelRowStyle style;
            style.scale = float(options_.scale);
            return render::page_text(render::grid_text(
                panel_rects(plant, style, static_cast<int>(area.w), static_cast<int>(area.h)), titles(),
                render::TitlePlace::above, std::round(style.title_size * style.scale), style.title_pad * style.scale));
        }, "set fewer style.views");

        // The turntable: one turn around the vertical axis over the film.
        Description plan = d_;
        plan.panels.clear();
        StepRunner run(plan, options_, out);
        render::PanelRowStyle row;
        row.scale = float(options_.scale);
        render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
        std::vector<render::Camera> film_cameras;
        run.run({.check = {},
                 .panel = {},
                 .frame =
                     [&](int step) {
                         if (film_cameras.empty())
                             film_cameras =
                                 turntable_cameras(plant, float(run.frame_width()) / float(run.frame_height()));
                         return FrameDrawing{[&, step](render::Surface& surface) {
                                                 turntable_frame(surface, plant, film_cameras[std::size_t(step)]);
                                             },
                                             4, true};
                     },
                 .advance = [] { return true; }});

        if (run.film_only()) return run.finish_film();  // a film segment's run: no figure
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        const std::vector<render::Rect> panels = panel_rects(plant, row, width, height);
        // Each panel, its camera and the plant's projected box in it, in the figure's pixels.
        std::vector<render::Camera> cameras;
        nlohmann::json panel_meta = nlohmann::json::array();
        for (std::size_t i = 0; i < s_.views.size(); ++i) {
            const render::Rect& r = panels[i];
            cameras.push_back(view_camera(plant, i, r.w / r.h));
            const render::Extent e = render::projected_extent(plant.balls, cameras.back(), r.w / r.h);
            panel_meta.push_back({{"azimuth_degrees", s_.views[i]},
                                  {"elevation_degrees", float(s_.elevation)},
                                  {"rect", {r.x, r.y, r.w, r.h}},
                                  {"plant_box",
                                   {r.x + (e.lo.x + 1) / 2 * r.w, r.y + (1 - e.hi.y) / 2 * r.h,
                                    r.x + (e.hi.x + 1) / 2 * r.w, r.y + (1 - e.lo.y) / 2 * r.h}}});
        }
        const FigureDrawing figure{width, height, true, [&](render::Surface& surface) {
                                       draw_views(surface, plant, panels, cameras, row, font);
                                   }};
        const glm::vec3 lo = plant.lo, hi = plant.hi;
        run.write_figure(figure, {{"params", params_.used()},
                                  {"style", style_.used()},
                                  {"panels", panel_meta},
                                  {"segments", drawing.segments.size()},
                                  {"polygons", drawing.polygons.size()},
                                  {"polygon_vertices", drawing.vertices.size()},
                                  {"state_sha256", drawing_hash(drawing)},
                                  {"symbols", p_.system.length(p_.depth)},
                                  {"bounds", {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}}});
    }

private:
    // The figure's view i in a panel of `aspect`.
    render::Camera view_camera(const Plant& plant, std::size_t i, float aspect) const {
        return render::frame_balls(plant.balls, float(s_.views[i]), float(s_.elevation), aspect, fill);
    }

    // The film's cameras, one a frame: each frame's share of one turn, every
    // one from the distance of the farthest, so the plant keeps its size as
    // it turns, centred in each.
    std::vector<render::Camera> turntable_cameras(const Plant& plant, float aspect) const {
        const int frames = d_.animation->last + 1;
        auto azimuth = [&](int step) { return 360.0f * float(step) / float(frames); };
        float distance = 0;
        for (int step = 0; step < frames; ++step) {
            const render::Camera c = render::frame_balls(plant.balls, azimuth(step), float(s_.elevation), aspect, fill);
            distance = std::max(distance, glm::length(c.eye - c.target));
        }
        std::vector<render::Camera> cameras;
        for (int step = 0; step < frames; ++step)
            cameras.push_back(
                render::frame_balls(plant.balls, azimuth(step), float(s_.elevation), aspect, fill, distance));
        return cameras;
    }

    // The film's frame: the plant seen through its camera.
    void turntable_frame(render::Surface& canvas, const Plant& plant, const render::Camera& camera) const {
        canvas.background({1, 1, 1, 1});
        const render::Rect view{0, 0, float(canvas.width()), float(canvas.height())};
        render::draw_tubes(canvas, view, plant.tubes, plant.facets, camera, studio_light(camera), s_.sides);
    }

    // One panel per azimuth, as wide as the widest view of the plant needs
    // (within min_aspect..max_aspect), so that the plant fills the height of
    // each.
    std::vector<render::Rect> panel_rects(const Plant& plant, render::PanelRowStyle row, int width, int height) const {
        float widest = min_aspect;
        for (std::size_t i = 0; i < s_.views.size(); ++i) {
            const render::Extent e = render::projected_extent(plant.balls, view_camera(plant, i, 1), 1);
            const glm::vec2 size = e.hi - e.lo;
            if (size.y > 0) widest = std::max(widest, size.x / size.y);
        }
        row.aspect = std::clamp(widest, min_aspect, max_aspect);
        return render::panel_row(width, height, int(s_.views.size()), true, row);
    }

    // The figure: the plant in each panel through its camera, titled.
    void draw_views(render::Surface& canvas, const Plant& plant, const std::vector<render::Rect>& panels,
                    const std::vector<render::Camera>& cameras, const render::PanelRowStyle& row,
                    render::Font& font) const {
        canvas.background({1, 1, 1, 1});
        render::Text text;
        const std::vector<std::string> title = titles();
        for (std::size_t i = 0; i < s_.views.size(); ++i) {
            render::draw_tubes(canvas, panels[i], plant.tubes, plant.facets, cameras[i], studio_light(cameras[i]),
                               s_.sides);
            text.add(font, title[i], {panels[i].centre().x, panels[i].y - row.title_pad * row.scale}, {0, 0, 0, 1},
                     render::Align::centre, render::Baseline::baseline);
        }
        text.draw(canvas);
    }

    // Each panel's title: its azimuth.
    std::vector<std::string> titles() const {
        std::vector<std::string> out;
        for (const double azimuth : s_.views) out.push_back("azimuth " + format_fixed(azimuth, 0) + "\u00b0");
        return out;
    }

    const Params p_;
    const Style s_;
    const Palette palette_;
    const std::uint64_t segments_;  // what the turtle will draw, counted without drawing
    const std::uint64_t vertices_;  // its polygons' vertices at most, likewise
};

std::unique_ptr<Scene> read_lsystem_3d(const Description& d, const SceneOptions& options) {
    return std::make_unique<LSystem3dScene>(d, options);
}

}  // namespace

SceneInfo lsystem_3d_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"lsystem_3d",
            read_lsystem_3d,
            {},
            {
                {"/segments", "segments", "integer", ""},
                {"/symbols", "symbols", "integer", ""},
            }};
}

}  // namespace scenes
