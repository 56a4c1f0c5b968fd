// Iterated function systems ("Plants hidden in mathematical formulas", part
// 3): the chaos game's points binned into the panel's pixels, drawn as a
// density (log of the count through a colormap) or as plain points.
#include <cmath>
#include <optional>
#include <sstream>

#include "render/layout.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/scene.hpp"
#include "sim/check.hpp"
#include "sim/ifs.hpp"
#include "sim/random.hpp"

namespace scenes {
namespace {

constexpr std::size_t max_maps = 64;      // what sim::Ifs takes
constexpr int max_points = 20'000'000;    // per panel, kept until the figure is drawn: 320 MB
constexpr int max_discard = 100'000'000;  // the model's own bound
constexpr double max_coordinate = 1e300;  // what sim::density takes for its box

struct Variant {
    std::string title;
    sim::Ifs ifs;
};

// A TOML value on one line, as a message shows it: "[1, 2]", at most 60 characters.
std::string one_line(const toml::node& node) {
    std::ostringstream printed;
    node.visit([&](const auto& n) { printed << n; });
    std::string text;  // "[ 1, 2 ]" over any number of lines becomes "[1, 2]"
    for (const char c : printed.str()) {
        const bool space = c == ' ' || c == '\n';
        if (space && (text.empty() || text.back() == ' ' || text.back() == '[')) continue;
        if (c == ']' && !text.empty() && text.back() == ' ') text.pop_back();
        text += space ? ' ' : c;
    }
    if (!text.empty() && text.back() == ' ') text.pop_back();
    return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

// [[a, b, c, d, e, f, p], ...] from a variant's table; a bad map is refused by its index ("maps[1]").
sim::Ifs read_maps(Settings& variant, const std::string& key) {
    const toml::node* given = variant.node(key);
    const toml::array* maps = given ? given->as_array() : nullptr;
    if (!maps)
        variant.refuse(key, given ? one_line(*given) : "(missing)",
                       "a list of maps [a, b, c, d, e, f, p], seven numbers each");
    if (maps->empty() || maps->size() > max_maps)
        variant.refuse("maps", std::to_string(maps->size()) + " maps",
                       "1 to " + std::to_string(max_maps) + " maps [a, b, c, d, e, f, p]");
    sim::Ifs ifs;
    for (std::size_t m = 0; m < maps->size(); ++m) {
        const toml::array* values = (*maps)[m].as_array();
        double v[7];
        for (std::size_t i = 0; i < 7; ++i) {
            const auto number = values && values->size() == 7 ? (*values)[i].value<double>() : std::nullopt;
            if (!number)
                variant.refuse(key + "[" + std::to_string(m) + "]", one_line((*maps)[m]),
                               "seven numbers [a, b, c, d, e, f, p]");
            v[i] = *number;
        }
        ifs.maps.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
    }
    return ifs;
}

const Schema<Variant> variant_schema =
    Schema<Variant>()
        .text("title", &Variant::title, "panel title")
        .key({"maps", "[[a, b, c, d, e, f, p], ...]: x' = a x + b y + e, y' = c x + d y + f, picked with probability p",
              "a list of lists of numbers", "1 to " + std::to_string(max_maps) + " maps [a, b, c, d, e, f, p]"},
             [](Settings& s, const std::string& key, Variant& v) { v.ifs = read_maps(s, key); })
        .check([](Settings& s, const std::string&, Variant& v) { check_model(s, [&] { v.ifs.validate(); }); });

struct Params {
    std::vector<Variant> variants;
    sim::ChaosGameParams game;
    std::vector<double> bounds;  // [xmin, xmax, ymin, ymax]; empty: the points' own box
    bool shared_bounds = false;  // without bounds: one box for every panel
};

const std::string bounds_allowed = "[xmin, xmax, ymin, ymax] with xmin < xmax and ymin < ymax, each from " +
                                   sim::shown(-max_coordinate) + " to " + sim::shown(max_coordinate);

const Schema<Params> param_schema = [] {
    using G = sim::ChaosGameParams;
    Schema<G> game;
    game.count("points", &G::points, "points per panel", 1, max_points);
    game.count("discard", &G::discard, "first points dropped", 0, max_discard);
    game.check(validated<G>());
    Schema<Params> s;
    // Each variant's title and maps, the maps checked by the model under the
    // variant's keys ("variants[1].maps[2].p").
    s.key({"variants", "list of {title, maps = [[a, b, c, d, e, f, p], ...]}, one panel each", "a list of tables",
           "one variant at least"},
          [](Settings& section, const std::string& key, Params& p) {
              const auto tables = section.tables(key);
              if (tables.empty())
                  section.refuse(key, "[]", "one variant at least, {title, maps = [[a, b, c, d, e, f, p], ...]}");
              for (std::size_t i = 0; i < tables.size(); ++i) {
                  Settings variant("params." + key + "[" + std::to_string(i) + "]", tables[i], variant_schema.keys());
                  p.variants.push_back(variant_schema.read(variant));
              }
          });
    s.part(game, &Params::game);
    s.key({"bounds", "[xmin, xmax, ymin, ymax] drawn in every panel; absent: the points' own bounds",
           "a list of numbers", bounds_allowed},
          [](Settings& section, const std::string& key, Params& p) {
              p.bounds = section.numbers(key, {});
              if (p.bounds.empty()) return;
              bool box = p.bounds.size() == 4 && p.bounds[1] > p.bounds[0] && p.bounds[3] > p.bounds[2];
              for (const double b : p.bounds) box = box && std::abs(b) <= max_coordinate;
              if (box) return;
              std::string value;  // on one line, however many numbers
              for (const double b : p.bounds) value += (value.empty() ? "[" : ", ") + sim::shown(b);
              section.refuse(key, value + "]", bounds_allowed);
          });
    s.flag("shared_bounds", &Params::shared_bounds,
           "true: every panel shows the box of all panels' points, at one scale; false: each panel its own points' "
           "box");
    return s;
}();

struct Style {
    FieldSpec field{render::colormap("Greens"), 0.0, {}, 1.0f, render::Sampling::nearest};
    bool points_mode = false;  // a pixel is on or off, not a log count
};

const Schema<Style> style_schema = Schema<Style>()
                                       .part(field_spec_schema(), &Style::field)
                                       .choice("mode", &Style::points_mode, {{"density", false}, {"points", true}},
                                               "density (log count through the colormap) or points");

// SHA-256 of the points' x and y, in the order the game made them.
std::string points_hash(const std::vector<glm::dvec2>& points) {
    std::vector<double> xy;
    xy.reserve(2 * points.size());
    for (const auto& p : points) xy.insert(xy.end(), {p.x, p.y});
    return state_hash(xy);
}

// The cloud's pixels: on or off in points mode, else the log of the count.
sim::Grid<double> binned(const std::vector<glm::dvec2>& cloud, int cols, int rows, glm::dvec2 lo, glm::dvec2 hi,
                         bool points_mode) {
    const sim::Density density = sim::density(cloud, cols, rows, lo, hi);
    sim::Grid<double> field(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double n = density.at(r, c);
            field(r, c) = points_mode ? (n > 0 ? 1.0 : 0.0) : std::log1p(n);
        }
    return field;
}

// Every variant's points, their metadata and the box of them all.
struct Clouds {
    std::vector<std::vector<glm::dvec2>> points;
    nlohmann::json meta = nlohmann::json::array();
    glm::dvec2 lo{1e300, 1e300}, hi{-1e300, -1e300};  // of them all
    std::vector<std::pair<glm::dvec2, glm::dvec2>> own;  // each panel's
};

// `box` widened about its centre, in x or in y, to width / height = aspect.
std::pair<glm::dvec2, glm::dvec2> with_aspect(std::pair<glm::dvec2, glm::dvec2> box, double aspect) {
    auto& [lo, hi] = box;
    const glm::dvec2 size = glm::max(hi - lo, glm::dvec2(1e-300)), centre = (lo + hi) / 2.0;
    const glm::dvec2 fitted = size.x / size.y < aspect ? glm::dvec2(aspect * size.y, size.y)
                                                        : glm::dvec2(size.x, size.x / aspect);
    return {centre - fitted / 2.0, centre + fitted / 2.0};
}

class IfsScene : public SceneBase {
public:
    IfsScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)) {}

    // Every panel's points, two doubles each, kept until the figure is drawn,
    // and one panel's copy for its hash. Measured at 20,000,000 points, 3
    // panels: 19.2 bytes a point above the program.
    std::vector<MemoryNeed> memory() const override {
        return {{std::to_string(p_.variants.size()) + " x " + std::to_string(p_.game.points) + " points",
                 16.0 * double(p_.game.points) * double(p_.variants.size())},
                {"a panel's points hashed", 16.0 * double(p_.game.points)}};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(p_.variants.size()));
        Clouds clouds = play(progress);
        // The box each panel shows: [params] bounds, else all the points' box
        // when shared, else each panel's own points' box, widened to the
        // panels' common aspect (the geometric mean of theirs) so that each
        // cloud keeps its shape and fills its panel one way.
        std::vector<std::pair<glm::dvec2, glm::dvec2>> boxes(clouds.points.size(), {clouds.lo, clouds.hi});
        if (!p_.bounds.empty()) {
            boxes.assign(clouds.points.size(), {{p_.bounds[0], p_.bounds[2]}, {p_.bounds[1], p_.bounds[3]}});
        } else if (!p_.shared_bounds && boxes.size() > 1) {  // one panel: its own box is all the points
            double log_aspect = 0;
            for (const auto& [lo, hi] : clouds.own) {
                const glm::dvec2 size = glm::max(hi - lo, glm::dvec2(1e-300));
                log_aspect += std::log(size.x / size.y) / double(clouds.own.size());
            }
            for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = with_aspect(clouds.own[i], std::exp(log_aspect));
        }
        const Page page = draw(clouds, boxes);
        const FigureDrawing figure = field_figure(page.panels, d_, options_);
        out.figure(figure, {{"params", params_.used()}, {"style", style_.used()}, {"panels", clouds.meta}});
        progress.finish();
    }

private:
    // The chaos game of each variant in turn, from one random stream.
    Clouds play(Progress& progress) const {
        sim::Random rng(d_.seed);  // one stream for all panels, in order
        Clouds clouds;
        for (const Variant& v : p_.variants) {
            std::vector<std::uint64_t> counts;
            clouds.points.push_back(sim::chaos_game(v.ifs, p_.game, rng, &counts));
            glm::dvec2 own_lo{1e300, 1e300}, own_hi{-1e300, -1e300};
            for (const auto& p : clouds.points.back()) {
                own_lo = glm::min(own_lo, p);
                own_hi = glm::max(own_hi, p);
            }
            clouds.lo = glm::min(clouds.lo, own_lo);
            clouds.hi = glm::max(clouds.hi, own_hi);
            clouds.own.push_back({own_lo, own_hi});
            nlohmann::json maps = nlohmann::json::array();
            for (const auto& m : v.ifs.maps) maps.push_back({m.a, m.b, m.c, m.d, m.e, m.f, m.p});
            clouds.meta.push_back({{"title", v.title},
                                   {"maps", maps},
                                   {"points", clouds.points.back().size()},
                                   {"map_counts", counts},
                                   {"points_bounds", {own_lo.x, own_hi.x, own_lo.y, own_hi.y}},
                                   {"state_sha256", points_hash(clouds.points.back())}});
            progress.advance();
        }
        return clouds;
    }

    // Each panel bins its points into as many cells as the panel has pixels;
    // every panel shows the box lo..hi, noted in its metadata.
    struct Page {
        std::vector<FieldSpec> specs;  // one per panel: a field layer points at its colormap
        std::vector<FieldPanel> panels;
    };
    Page draw(Clouds& clouds, const std::vector<std::pair<glm::dvec2, glm::dvec2>>& boxes) const {
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        render::PanelRowStyle row;
        row.scale = float(options_.scale);
        row.aspect = float((boxes[0].second.x - boxes[0].first.x) / (boxes[0].second.y - boxes[0].first.y));
        const auto rects = render::panel_row(width, height, int(clouds.points.size()), true, row);
        Page page{std::vector<FieldSpec>(clouds.points.size(), s_.field), {}};
        std::vector<FieldSpec>& specs = page.specs;
        std::vector<FieldPanel>& panels = page.panels;
        for (std::size_t i = 0; i < clouds.points.size(); ++i) {
            const int cols = std::max(1, int(rects[i].w)), rows = std::max(1, int(rects[i].h));
            const auto& [lo, hi] = boxes[i];
            const sim::Grid<double> field = binned(clouds.points[i], cols, rows, lo, hi, s_.points_mode);
            if (s_.points_mode) specs[i].colormap = render::listed_colormap("points", {{1, 1, 1}, {0.0f, 0.45f, 0.1f}});
            panels.push_back({p_.variants[i].title, {field_layer(field, specs[i])}});
            clouds.meta[i]["drawn_bounds"] = {lo.x, hi.x, lo.y, hi.y};
        }
        return page;
    }

    const Params p_;
    const Style s_;
};

std::unique_ptr<Scene> read_ifs(const Description& d, const SceneOptions& options) {
    return std::make_unique<IfsScene>(d, options);
}

}  // namespace

SceneInfo ifs_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"ifs",
            read_ifs,
            {"colormap"},
            {
                {"/panels/*/points_bounds",
                 "extent, {title}",
                 "bounds",
                 "",
                 {{"title=Barnsley fern", "x -2.18 to 2.66, y 0 to 9.96 (catalog)"}}},
                {"/panels/*/points", "points, {title}", "integer", ""},
            }};
}

}  // namespace scenes
