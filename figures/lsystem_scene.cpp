// Bracketed L-systems drawn by a turtle ("Plants hidden in mathematical
// formulas", part 1, and The Algorithmic Beauty of Plants): one panel per
// plant, branches as lines of their pen width with round joints, all in one
// draw call.
#include <cmath>

#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "render/layout.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "sim/check.hpp"
#include "sim/lsystem.hpp"
#include "sim/turtle.hpp"

namespace figures {
namespace {

const std::vector<Key> plant_keys = {
    {"title", "panel title"},
    {"axiom", "the depth-0 string"},
    {"rules", "rewriting rules, e.g. [\"F -> FF+[+F-F]-[-F+F]\"]"},
    {"rule", "a single rule, replacing rules (--set rule=\"F -> FF\")"},
    {"depth", "rewriting depth"},
    {"angle", "turn of + and - in degrees"},
    {"plus", "\"right\" (the article's turtle: + is rt) or \"left\" (ABOP)"},
    {"length", "segment length at level 0"},
    {"length_scale", "segment length factor per level"},
    {"width", "pen width (rewrite reading)"},
    {"width_per_level", "pen width per level (the article's pensize(2n))"},
    {"reading", "\"article\" (its recursive turtle) or \"rewrite\" (rewrite depth times, then draw)"},
};

struct Plant {
    std::string title;
    sim::LSystem system;
    int depth = 3;
    sim::Turtle2Params turtle;
    bool article = false;
    nlohmann::json used;
};

// Values from the plant's own table, else the figure's [params], else the default.
Plant read_plant(const toml::table& own, Settings& shared, const std::string& where) {
    Settings s(where, own, plant_keys);
    auto text = [&](const std::string& key, const std::string& fallback) {
        return shared.has(key) ? shared.text(key, fallback) : s.text(key, fallback);
    };
    auto number = [&](const std::string& key, double fallback) {
        return shared.has(key) ? shared.number(key, fallback) : s.number(key, fallback);
    };
    Plant p;
    p.title = s.text("title", "");
    std::vector<std::string> rules = shared.has("rules") ? shared.texts("rules", {}) : s.texts("rules", {});
    if (shared.has("rule"))
        rules = {shared.text("rule", "")};
    else if (s.has("rule"))
        rules = {s.text("rule", "")};
    p.system = sim::LSystem::parse(text("axiom", "F"), rules);
    p.depth = static_cast<int>(number("depth", 3));
    sim::require_integer("depth", p.depth, 0, 64);
    const std::string plus = text("plus", "right");
    if (plus != "right" && plus != "left")
        throw UsageError(where + ".plus = \"" + plus + "\" is not allowed: use \"right\" or \"left\"");
    p.turtle.angle_degrees = number("angle", 22) * (plus == "left" ? -1 : 1);
    p.turtle.length = number("length", 12);
    p.turtle.length_scale = number("length_scale", 1);
    p.turtle.width = number("width", 2);
    p.turtle.width_per_level = number("width_per_level", 2);
    p.turtle.validate();
    const std::string reading = text("reading", "rewrite");
    if (reading != "article" && reading != "rewrite")
        throw UsageError(where + ".reading = \"" + reading + "\" is not allowed: use \"article\" or \"rewrite\"");
    p.article = reading == "article";
    p.used = s.used();
    p.used["rules"] = rules;
    return p;
}

// Fits the segments into `panel` (same scale both ways) and adds them, width
// scaled alike but never under `min_width` pixels, with round joints.
void add_plant(render::Shapes& shapes, const render::Rect& panel, const std::vector<sim::Segment2>& segments,
               const glm::vec4& colour, float min_width) {
    const sim::Bounds2 box = sim::bounds(segments);
    const glm::dvec2 span = glm::max(box.hi - box.lo, glm::dvec2(1e-9));
    const double scale = std::min(panel.w / span.x, panel.h / span.y) * 0.96;
    const glm::dvec2 mid = (box.lo + box.hi) / 2.0;
    auto at = [&](glm::dvec2 p) {
        return panel.centre() + glm::vec2(float((p.x - mid.x) * scale), float(-(p.y - mid.y) * scale));
    };
    for (const auto& s : segments) {
        const float w = std::max(min_width, float(s.width * scale));
        const glm::vec2 a = at(s.a), b = at(s.b);
        shapes.line(a, b, w, colour);
        shapes.disc(a, w / 2, colour);
        shapes.disc(b, w / 2, colour);
    }
}

// SHA-256 of the turtle's segments in drawing order: from, to, width, level.
std::string segments_hash(const std::vector<sim::Segment2>& segments) {
    std::vector<double> values;
    values.reserve(6 * segments.size());
    for (const auto& s : segments) values.insert(values.end(), {s.a.x, s.a.y, s.b.x, s.b.y, s.width, double(s.level)});
    return state_hash(values);
}

}  // namespace

void render_lsystem(const Description& d, const OutputOptions& options, Progress& progress) {
    std::vector<Key> keys = plant_keys;
    keys.erase(keys.begin());  // no shared title
    keys.push_back({"plants", "list of plants, one panel each, each a table of the keys above"});
    Settings params("params", d.params, keys);
    Settings style("style", d.style, {{"colour", "line colour"}, {"min_width", "thinnest line, pixels at scale 1"}});
    std::vector<Plant> plants;
    try {
        auto tables = params.tables("plants");
        if (tables.empty()) tables.push_back(toml::table{});
        for (std::size_t i = 0; i < tables.size(); ++i)
            plants.push_back(read_plant(tables[i], params, "params.plants[" + std::to_string(i) + "]"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const glm::vec4 colour = style_colour(style, "colour", "green");
    const float min_width = float(style.number("min_width", 0.6) * options.scale);
    progress.start(d.id, static_cast<long long>(plants.size()));

    const int width = figure_width(d, options), height = figure_height(d, options);
    render::Canvas canvas(width, height);
    canvas.clear({1, 1, 1, 1});
    render::PanelRowStyle row;
    row.scale = float(options.scale);
    std::vector<std::vector<sim::Segment2>> drawings;
    double aspect = 0;
    std::vector<MemoryNeed> needs;
    for (const auto& p : plants)
        needs.push_back({"plant of depth " + std::to_string(p.depth),
                         static_cast<double>(sim::segment_count(p.system, p.depth, p.article)) *
                             (sizeof(sim::Segment2) + render::Shapes::bytes_per_line)});
    require_memory(d, options, needs);
    for (const auto& p : plants) {
        try {
            drawings.push_back(sim::interpret_2d(p.system, p.depth, p.turtle, p.article));
        } catch (const std::invalid_argument& e) {
            throw UsageError(d.id + ": " + e.what());
        }
        const auto box = sim::bounds(drawings.back());
        aspect = std::max(aspect, (box.hi.x - box.lo.x) / std::max(1e-9, box.hi.y - box.lo.y));
        progress.advance();
    }
    row.aspect = float(std::clamp(aspect, 0.2, 3.0));
    const int columns = std::min<int>(int(plants.size()), params.has("plants") ? 3 : 1);
    const auto rects =
        render::panel_grid({0, 0, float(width), float(height)}, int(plants.size()), std::max(1, columns), true, row);
    render::Shapes shapes;
    nlohmann::json panel_meta = nlohmann::json::array();
    for (std::size_t i = 0; i < plants.size(); ++i) {
        add_plant(shapes, rects[i], drawings[i], colour, min_width);
        const auto box = sim::bounds(drawings[i]);
        panel_meta.push_back({{"title", plants[i].title},
                              {"plant", plants[i].used},
                              {"depth", plants[i].depth},
                              {"reading", plants[i].article ? "article" : "rewrite"},
                              {"symbols", plants[i].article ? plants[i].system.length_recursive(plants[i].depth)
                                                            : plants[i].system.length(plants[i].depth)},
                              {"segments", drawings[i].size()},
                              {"bounds", {box.lo.x, box.lo.y, box.hi.x, box.hi.y}},
                              {"state_sha256", segments_hash(drawings[i])}});
    }
    shapes.draw(canvas);
    render::Text text;
    render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
    for (std::size_t i = 0; i < plants.size(); ++i)
        text.add(font, plants[i].title, {rects[i].centre().x, rects[i].y - row.title_pad * row.scale}, {0, 0, 0, 1},
                 render::Align::centre, render::Baseline::baseline);
    text.draw(canvas);
    write_figure(d, options, canvas.read(),
                 {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}});
    progress.finish();
}

}  // namespace figures
