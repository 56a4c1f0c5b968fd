// Bracketed L-systems drawn by a turtle ("Plants hidden in mathematical
// formulas", part 1, and The Algorithmic Beauty of Plants): one panel per
// plant, branches as lines of their pen width with round joints, all in one
// draw call.
#include <cmath>
#include <limits>

#include "render/layout.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/scene.hpp"
#include "sim/check.hpp"
#include "sim/lsystem.hpp"
#include "sim/turtle.hpp"

namespace scenes {
namespace {

constexpr int max_depth = 64;  // far past any budget: the counts are cheap, the drawing is not

// A plant's keys, as its own table or the figure's [params] gives them.
struct PlantValues {
    std::string title;
    std::string axiom = "F";
    std::vector<std::string> rules;
    double depth = 3;  // checked to be an integer
    sim::Turtle2Params turtle;
    bool plus_left = false;  // ABOP's '+': the angle negated
    bool article = false;    // the article's recursive turtle, not the rewrite reading
};

const Schema<PlantValues> plant_schema = [] {
    using T = sim::Turtle2Params;
    Schema<T> turtle;
    turtle.number("angle", &T::angle_degrees, "turn of + and - in degrees");
    turtle.number("length", &T::length, "segment length at level 0");
    turtle.number("length_scale", &T::length_scale, "segment length factor per level");
    turtle.number("width", &T::width, "pen width (rewrite reading)");
    turtle.number("width_per_level", &T::width_per_level, "pen width per level (the article's pensize(2n))");
    turtle.text("draw", &T::draw, "the symbols that draw a step, e.g. \"FG\"");
    turtle.text("move", &T::move, "the symbols that move a step without drawing");
    Schema<PlantValues> s;
    s.text("title", &PlantValues::title, "panel title");
    s.text("axiom", &PlantValues::axiom, "the depth-0 string");
    s.texts("rules", &PlantValues::rules, "rewriting rules, e.g. [\"F -> FF+[+F-F]-[-F+F]\"]");
    s.key({"rule", "a single rule, replacing rules (--set rule=\"F -> FF\")", "text"},
          [](Settings& section, const std::string& key, PlantValues& v) {
              if (section.has(key)) v.rules = {section.text(key, "")};
          });
    // An integer, read as a number so that 2.5 is refused as not one.
    s.key({"depth", "rewriting depth", "an integer", integers_allowed(0, max_depth), 3},
          [](Settings& section, const std::string& key, PlantValues& v) {
              v.depth = section.number(key, v.depth);
              if (v.depth != std::floor(v.depth) || !(std::abs(v.depth) <= 1e9))
                  section.refuse(key, "an integer from 0 to " + std::to_string(max_depth));
          });
    s.choice("plus", &PlantValues::plus_left, {{"left", true}, {"right", false}},
             "right (the article's turtle: + is rt) or left (ABOP)");
    s.part(turtle, &PlantValues::turtle);
    s.choice("reading", &PlantValues::article, {{"article", true}, {"rewrite", false}},
             "article (its recursive turtle) or rewrite (rewrite depth times, then draw)");
    return s;
}();

// [params]: every plant key but the title, shared by all plants, and the plants.
std::vector<Key> param_keys() {
    std::vector<Key> keys = plant_schema.keys();
    keys.erase(keys.begin());  // no shared title
    keys.push_back({"plants", "list of plants, one panel each, each a table of the keys above", "a list of tables",
                    "one plant at least; absent: one plant of the keys above"});
    return keys;
}

struct Style {
    Colour colour = scenes::colour("green");
    double min_width = 0.6;
};
const Schema<Style> style_schema =
    Schema<Style>()
        .field({"colour", "line colour", "a colour"}, &Style::colour, read_colour)
        .number("min_width", &Style::min_width, "thinnest line, pixels at scale 1", 0.0, 100.0);

// The most segments a plant may draw (the turtle's own budget, 5,000,000,
// would take minutes to draw on llvmpipe and hundreds of MB of PDF).
constexpr std::uint64_t plant_segment_budget = 800'000;

// Memory a drawn segment takes, see memory(): the turtle's Segment2 and
// the 6 doubles hashed, each vector up to twice its size while it grows,
// and the round segment Shapes records (an op and its two points).
constexpr double segment_bytes = 2.0 * (sizeof(sim::Segment2) + 6 * sizeof(double)) + sizeof(render::Shapes::Op) +
                                 2 * sizeof(glm::vec2);
// The triangles a segment becomes when drawn: its line and a disc at each
// end, at their fewest.
constexpr double segment_triangles =
    (render::Shapes::line_vertices + 2 * render::Shapes::min_disc_vertices) / 3.0;

struct Plant {
    std::string title;
    sim::LSystem system;
    int depth = 3;
    sim::Turtle2Params turtle;
    bool article = false;
    std::uint64_t segments = 0;  // what the turtle will draw, counted without drawing
    nlohmann::json used;
};

// One plant's keys. A key of the figure's [params] applies to every plant and
// wins over the plant's own table (so --set depth=5 changes them all); else
// the plant's table; else the default. Mistakes name the key where it was
// written: "depth" or "plants[2].depth".
class PlantKeys {
public:
    // `own_first`: the plant's own keys win, to check the values that
    // [params] overrides (see check_overridden).
    PlantKeys(const toml::table& own, Settings& shared, std::size_t index, bool own_first = false)
        : where_("plants[" + std::to_string(index) + "]"),
          own_("params." + where_, own, plant_schema.keys()),
          shared_(shared),
          own_first_(own_first) {}

    // The section that gives `key` (not "title", which only a plant has).
    Settings& from(const std::string& key) {
        if (own_first_) return own_.has(key) ? own_ : shared_;
        return shared_.has(key) ? shared_ : own_;
    }
    // Whether [params] gives a key that the plant's own table gives too.
    bool overridden() const {
        for (const Key& k : own_.allowed())
            if (k.name != "title" && shared_.has(k.name) && own_.has(k.name)) return true;
        return false;
    }
    Settings& own() { return own_; }

    // The model's check; `names` maps every parameter name it can refuse to
    // the plant's key ("rules[1]" to "rules[1]" or "rule", "angle_degrees" to "angle").
    void check(const std::function<void()>& model_check, const KeyNames& names) const {
        KeyNames written;
        for (const auto& [model_name, key] : names) written.push_back({model_name, written_key(key)});
        check_model(shared_, model_check, written);
    }
    // `key` as [params] names it, "depth" or "plants[2].depth"; `key` may carry an index ("rules[1]").
    std::string written_key(const std::string& key) const {
        const std::string name = key.substr(0, key.find('['));
        const bool shared = own_first_ ? !own_.has(name) && shared_.has(name) : shared_.has(name);
        return shared ? key : where_ + "." + key;
    }

private:
    std::string where_;
    Settings own_;
    Settings& shared_;
    bool own_first_;
};

// A plant whose string holds none of its drawing symbols would be an empty
// panel: refused, naming the symbols its string has and the key that draws.
[[noreturn]] void refuse_drawing_nothing(PlantKeys& keys, const Plant& p) {
    std::string symbols;
    const auto counts = p.article ? p.system.counts_recursive(p.depth) : p.system.counts(p.depth);
    for (const auto& [symbol, count] : counts)
        if (count > 0 && std::string_view(sim::turtle_commands).find(symbol) == std::string_view::npos)
            symbols += symbol;
    const std::string shown = "\"" + p.turtle.draw + "\"";
    keys.from("draw").refuse(
        "draw", shown,
        symbols.empty() ? "a system that draws: its string at depth " + std::to_string(p.depth) +
                              " has no symbol but the turtle's commands; give it steps, e.g. axiom = \"F\""
                        : "symbols its string has, which draw a step: it has " + symbols + " (e.g. draw = \"" +
                              symbols + "\"; move = \"...\" for those that move without drawing)");
}

// The plant's system, depth, turtle and reading from `keys`, each checked
// by the model with the names as written: the angle as given, before ABOP's
// '+' (plus = "left") negates it.
void read_checked(PlantKeys& keys, Plant& p, std::vector<std::string>& rules) {
    const PlantValues v = plant_schema.read_each(
        [&](const std::string& key) -> Settings& { return key == "title" ? keys.own() : keys.from(key); });
    rules = v.rules;
    const bool single = keys.from("rule").has("rule");
    KeyNames names;
    for (std::size_t i = 0; i < rules.size(); ++i) {
        const std::string model_name = "rules[" + std::to_string(i) + "]";
        names.push_back({model_name, single ? "rule" : model_name});
    }
    names.push_back({"axiom", "axiom"});
    keys.check([&] { p.system = sim::LSystem::parse(v.axiom, rules); }, names);
    keys.check([&] { sim::require_integer("depth", static_cast<long long>(v.depth), 0, max_depth); },
               {{"depth", "depth"}});
    p.depth = static_cast<int>(v.depth);
    p.turtle = v.turtle;
    keys.check([&] { p.turtle.validate(); }, {{"angle_degrees", "angle"},
                                              {"length", "length"},
                                              {"length_scale", "length_scale"},
                                              {"width", "width"},
                                              {"width_per_level", "width_per_level"},
                                              {"draw", "draw"},
                                              {"move", "move"}});
    p.turtle.angle_degrees *= v.plus_left ? -1 : 1;
    p.article = v.article;
    p.title = v.title;
}

// A plant's own values that [params] overrides (--set depth=5 sets every
// plant's) are drawn by no one, but checked all the same: read again with the
// plant's own keys first, so a bad one is refused naming plants[i].key.
void check_overridden(const toml::table& own, const Settings& shared, std::size_t index) {
    Settings unrecorded = shared;  // what this reads is no figure's setting: the metadata keeps to shared's
    PlantKeys own_first(own, unrecorded, index, true);
    if (!own_first.overridden()) return;
    Plant unused;
    std::vector<std::string> rules;
    read_checked(own_first, unused, rules);
}

Plant read_plant(const toml::table& own, Settings& shared, std::size_t index) {
    check_overridden(own, shared, index);
    PlantKeys keys(own, shared, index);
    Plant p;
    std::vector<std::string> rules;
    read_checked(keys, p, rules);
    p.turtle.segment_budget = plant_segment_budget;
    p.segments = sim::segment_count(p.system, p.depth, p.article, p.turtle.draw);
    if (p.segments == 0) refuse_drawing_nothing(keys, p);
    // The turtle's own refusal (sim/turtle.cpp), here in phase 1, naming the key.
    check_model(keys.from("depth"), [&] { sim::require_segment_budget(p.depth, p.segments, p.turtle.segment_budget); });
    p.used = keys.own().used();
    p.used["rules"] = rules;
    return p;
}

std::vector<Plant> read_plants(Settings& params) {
    auto tables = params.tables("plants");
    if (params.has("plants") && tables.empty())
        params.refuse("plants", "one plant at least; leave plants out for one plant of the [params] settings");
    if (tables.empty()) tables.push_back(toml::table{});
    std::vector<Plant> plants;
    for (std::size_t i = 0; i < tables.size(); ++i) plants.push_back(read_plant(tables[i], params, i));
    return plants;
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
    // One allocation for the whole plant: a doubling vector would peak at up
    // to three times its primitives while it copies.
    shapes.reserve(segments.size(), 2 * segments.size());
    for (const auto& s : segments) {
        const float w = std::max(min_width, float(s.width * scale));
        shapes.round_segment(at(s.a), at(s.b), w, colour);
    }
}

// SHA-256 of the turtle's segments in drawing order: from, to, width, level.
std::string segments_hash(const std::vector<sim::Segment2>& segments) {
    std::vector<double> values;
    values.reserve(6 * segments.size());
    for (const auto& s : segments) values.insert(values.end(), {s.a.x, s.a.y, s.b.x, s.b.y, s.width, double(s.level)});
    return state_hash(values);
}

using Drawings = std::vector<std::vector<sim::Segment2>>;

// The panels' shape: the widest plant's width over height, within 0.2..3.
float panel_aspect(const Drawings& drawings) {
    double aspect = 0;
    for (const auto& drawing : drawings) {
        const auto box = sim::bounds(drawing);
        aspect = std::max(aspect, (box.hi.x - box.lo.x) / std::max(1e-9, box.hi.y - box.lo.y));
    }
    return float(std::clamp(aspect, 0.2, 3.0));
}

class LSystemScene : public SceneBase {
public:
    LSystemScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_keys(), style_schema.keys()),
          plants_(read_plants(params_)),
          s_(style_schema.read(style_)),
          min_width_(float(s_.min_width * options.scale)) {
        // The titles must fit before anything runs; the plants' shapes are
        // not known yet, so square panels stand in for them.
        require_text_fits(d, options, [&](const render::Rect& area) { return render::page_text(title_layout(area, 1.0f)); });
    }

    // Each plant's segments, from the turtle and as Shapes records them
    // (segment_bytes), and the triangles of one batch as they are drawn
    // (at most triangles_per_finish: the GL backend tessellates batch by
    // batch), in figgen's buffer and again in llvmpipe's copy. Measured
    // (make bench's memory sweep, peak RSS): pl-lsys-lycopodium 102 MiB at
    // depth 3, 200 at depth 6 (55,986 segments), 227 at depth 7 (335,922),
    // 260 for F -> FF at depth 19 (524,288): about 100 to 175 bytes a
    // segment past the first batch, against segment_bytes' 256.
    std::vector<MemoryNeed> memory() const override {
        std::vector<MemoryNeed> needs;
        double triangles = 0;
        for (const auto& p : plants_) {
            needs.push_back({"plant of depth " + std::to_string(p.depth) + ", " + std::to_string(p.segments) +
                                 " segments",
                             static_cast<double>(p.segments) * segment_bytes});
            triangles += static_cast<double>(p.segments) * segment_triangles;
        }
        needs.push_back({"a batch of the plants' triangles, in figgen's buffer and llvmpipe's",
                         2.0 * 3.0 * render::Shapes::bytes_per_vertex *
                             std::min(triangles, static_cast<double>(render::triangles_per_finish))});
        needs.push_back({"llvmpipe's queue of binned triangles", render::queued_triangles_bytes});
        return needs;
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(plants_.size()));
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        render::PanelRowStyle row;
        row.scale = float(options_.scale);
        const Drawings drawings = draw_turtles(progress);
        row.aspect = panel_aspect(drawings);
        require_text_fits(d_, options_, [&](const render::Rect& area) { return render::page_text(title_layout(area, row.aspect)); });
        const std::vector<render::Rect> rects = title_layout({0, 0, float(width), float(height)}, row.aspect).panels;
        render::Shapes shapes;
        const nlohmann::json panel_meta = add_plants(shapes, rects, drawings);
        const FigureDrawing figure{width, height, false, [&](render::Surface& surface) {
                                       surface.background({1, 1, 1, 1});
                                       shapes.draw(surface);
                                       draw_titles(surface, rects, row);
                                   }};
        out.figure(figure, {{"params", params_.used()}, {"style", style_.used()}, {"panels", panel_meta}});
        progress.finish();
    }

private:
    render::PanelRowStyle row_style(float aspect) const {
        render::PanelRowStyle row;
        row.scale = float(options_.scale);
        row.aspect = aspect;
        return row;
    }

    // The plants' panels in `area` and their titles above them.
    render::GridText title_layout(const render::Rect& area, float aspect) const {
        const render::PanelRowStyle row = row_style(aspect);
        std::vector<std::string> titles;
        for (const Plant& p : plants_) titles.push_back(p.title);
        return titled_grid_text(area, titles, figure_columns(d_, area, int(plants_.size()), true, row), true, row);
    }

    Drawings draw_turtles(Progress& progress) const {
        Drawings drawings;
        for (const auto& p : plants_) {
            drawings.push_back(sim::interpret_2d(p.system, p.depth, p.turtle, p.article));
            progress.advance();
        }
        return drawings;
    }

    // Adds every plant to `shapes` in its panel; returns the panels' metadata.
    nlohmann::json add_plants(render::Shapes& shapes, const std::vector<render::Rect>& rects,
                              const Drawings& drawings) const {
        nlohmann::json panel_meta = nlohmann::json::array();
        for (std::size_t i = 0; i < plants_.size(); ++i) {
            const Plant& p = plants_[i];
            add_plant(shapes, rects[i], drawings[i], s_.colour.rgba, min_width_);
            const auto box = sim::bounds(drawings[i]);
            const std::uint64_t symbols = p.article ? p.system.length_recursive(p.depth) : p.system.length(p.depth);
            panel_meta.push_back({{"title", p.title},
                                  {"plant", p.used},
                                  {"depth", p.depth},
                                  {"reading", p.article ? "article" : "rewrite"},
                                  {"symbols", symbols},
                                  {"segments", drawings[i].size()},
                                  {"bounds", {box.lo.x, box.lo.y, box.hi.x, box.hi.y}},
                                  {"state_sha256", segments_hash(drawings[i])}});
        }
        return panel_meta;
    }

    void draw_titles(render::Surface& canvas, const std::vector<render::Rect>& rects,
                     const render::PanelRowStyle& row) const {
        render::Text text;
        render::Font& font = render::font_of_size(std::round(row.title_size * row.scale));
        for (std::size_t i = 0; i < plants_.size(); ++i)
            text.add(font, plants_[i].title, {rects[i].centre().x, rects[i].y - row.title_pad * row.scale},
                     {0, 0, 0, 1}, render::Align::centre, render::Baseline::baseline);
        text.draw(canvas);
    }

    const std::vector<Plant> plants_;
    const Style s_;
    const float min_width_;  // pixels, scaled
};

std::unique_ptr<Scene> read_lsystem(const Description& d, const SceneOptions& options) {
    return std::make_unique<LSystemScene>(d, options);
}

}  // namespace

SceneInfo lsystem_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"lsystem",
            read_lsystem,
            {},
            {
                {"/panels/*/segments", "segments, {title}", "integer", ""},
            }};
}

}  // namespace scenes
