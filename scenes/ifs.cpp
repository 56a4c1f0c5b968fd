// Iterated function systems ("Plants hidden in mathematical formulas", part
// 3): the chaos game's points binned into the panel's pixels, drawn as a
// density (log of the count through a colormap) or as plain points.
#include <cmath>
#include <optional>
#include <sstream>

#include "scenes/field_spec.hpp"
#include "scenes/field_stats.hpp"
#include "scenes/model_check.hpp"
#include "scenes/scene.hpp"
#include "scenes/figure_caption.hpp"
#include "render/layout.hpp"
#include "sim/check.hpp"
#include "sim/ifs.hpp"
#include "sim/random.hpp"

namespace scenes {
namespace {

const std::vector<Key> param_keys = {
    {"variants", "list of {title, maps = [[a, b, c, d, e, f, p], ...]}, one panel each"},
    {"points", "points per panel"},
    {"discard", "first points dropped"},
    {"bounds", "[xmin, xmax, ymin, ymax] drawn in every panel; absent: the points' own bounds"},
    {"shared_bounds", "true: every panel shows the box of all panels' points, at one scale; false (default): each "
                      "panel its own points' box"},
};

const std::vector<Key> variant_keys = {
    {"title", "panel title"},
    {"maps", "[[a, b, c, d, e, f, p], ...]: x' = a x + b y + e, y' = c x + d y + f, picked with probability p"},
};

std::vector<Key> style_keys() {
    auto keys = field_spec_keys();
    keys.push_back({"mode", "\"density\" (log count through the colormap) or \"points\""});
    return keys;
}

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
sim::Ifs read_maps(Settings& variant, const toml::table& table) {
    const toml::array* maps = table["maps"].as_array();
    if (!maps)
        variant.refuse("maps", variant.has("maps") ? one_line(*table.get("maps")) : "(missing)",
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
                variant.refuse("maps[" + std::to_string(m) + "]", one_line((*maps)[m]),
                               "seven numbers [a, b, c, d, e, f, p]");
            v[i] = *number;
        }
        ifs.maps.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
    }
    return ifs;
}

// Each variant's title and maps, the maps checked by the model under the
// variant's keys ("variants[1].maps[2].p").
std::vector<Variant> read_variants(Settings& params) {
    const auto tables = params.tables("variants");
    if (tables.empty())
        params.refuse("variants", "[]", "one variant at least, {title, maps = [[a, b, c, d, e, f, p], ...]}");
    std::vector<Variant> variants;
    for (std::size_t i = 0; i < tables.size(); ++i) {
        Settings variant("params.variants[" + std::to_string(i) + "]", tables[i], variant_keys);
        Variant v{variant.text("title", ""), read_maps(variant, tables[i])};
        check_model(variant, [&] { v.ifs.validate(); });
        variants.push_back(std::move(v));
    }
    return variants;
}

sim::ChaosGameParams read_game(Settings& params) {
    sim::ChaosGameParams game;
    game.points = static_cast<std::uint64_t>(params.count_in("points", 200000, 1, max_points));
    game.discard = static_cast<std::uint64_t>(params.count_in("discard", 100, 0, max_discard));
    check_model(params, [&] { game.validate(); });
    return game;
}

// [xmin, xmax, ymin, ymax], or empty for the points' own bounds.
std::vector<double> read_bounds(Settings& params) {
    const auto bounds = params.numbers("bounds", {});
    if (bounds.empty()) return bounds;
    bool box = bounds.size() == 4 && bounds[1] > bounds[0] && bounds[3] > bounds[2];
    for (const double b : bounds) box = box && std::abs(b) <= max_coordinate;
    if (box) return bounds;
    std::string value;  // on one line, however many numbers
    for (const double b : bounds) value += (value.empty() ? "[" : ", ") + sim::shown(b);
    params.refuse("bounds", value + "]",
                  "[xmin, xmax, ymin, ymax] with xmin < xmax and ymin < ymax, each from " + sim::shown(-max_coordinate) +
                      " to " + sim::shown(max_coordinate));
}

// True for "points" (a pixel is on or off), false for "density".
bool read_points_mode(Settings& style) {
    const std::string mode = style.text("mode", "density");
    if (mode != "density" && mode != "points") style.refuse("mode", "\"density\" or \"points\"");
    return mode == "points";
}

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
        : SceneBase(d, options, param_keys, style_keys()),
          game_(read_game(params_)),
          bounds_(read_bounds(params_)),
          shared_bounds_(params_.flag("shared_bounds", false)),
          points_mode_(read_points_mode(style_)),
          spec_(read_field_spec(style_, {render::colormap("Greens"), 0.0, {}, 1.0f, render::Sampling::nearest})),
          variants_(read_variants(params_)) {}

    // Every panel's points, two doubles each, kept until the figure is drawn,
    // and one panel's copy for its hash. Measured at 20,000,000 points, 3
    // panels: 19.2 bytes a point above the program.
    std::vector<MemoryNeed> memory() const override {
        return {{std::to_string(variants_.size()) + " x " + std::to_string(game_.points) + " points",
                 16.0 * double(game_.points) * double(variants_.size())},
                {"a panel's points hashed", 16.0 * double(game_.points)}};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(variants_.size()));
        Clouds clouds = play(progress);
        // The box each panel shows: [params] bounds, else all the points' box
        // when shared, else each panel's own points' box, widened to the
        // panels' common aspect (the geometric mean of theirs) so that each
        // cloud keeps its shape and fills its panel one way.
        std::vector<std::pair<glm::dvec2, glm::dvec2>> boxes(clouds.points.size(), {clouds.lo, clouds.hi});
        if (!bounds_.empty()) {
            boxes.assign(clouds.points.size(), {{bounds_[0], bounds_[2]}, {bounds_[1], bounds_[3]}});
        } else if (!shared_bounds_ && boxes.size() > 1) {  // one panel: its own box is all the points
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
        for (const Variant& v : variants_) {
            std::vector<std::uint64_t> counts;
            clouds.points.push_back(sim::chaos_game(v.ifs, game_, rng, &counts));
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
        Page page{std::vector<FieldSpec>(clouds.points.size(), spec_), {}};
        std::vector<FieldSpec>& specs = page.specs;
        std::vector<FieldPanel>& panels = page.panels;
        for (std::size_t i = 0; i < clouds.points.size(); ++i) {
            const int cols = std::max(1, int(rects[i].w)), rows = std::max(1, int(rects[i].h));
            const auto& [lo, hi] = boxes[i];
            const sim::Grid<double> field = binned(clouds.points[i], cols, rows, lo, hi, points_mode_);
            if (points_mode_)
                specs[i].colormap = render::listed_colormap("points", {{1, 1, 1}, {0.0f, 0.45f, 0.1f}});
            panels.push_back({variants_[i].title, {field_layer(field, specs[i])}});
            clouds.meta[i]["drawn_bounds"] = {lo.x, hi.x, lo.y, hi.y};
        }
        return page;
    }

    const sim::ChaosGameParams game_;
    const std::vector<double> bounds_;  // [xmin, xmax, ymin, ymax]; empty: the points' own box
    const bool shared_bounds_;          // without bounds_: one box for every panel
    const bool points_mode_;
    const FieldSpec spec_;
    const std::vector<Variant> variants_;
};

std::unique_ptr<Scene> read_ifs(const Description& d, const SceneOptions& options) {
    return std::make_unique<IfsScene>(d, options);
}

}  // namespace

SceneInfo ifs_scene() {
    // Its key numbers (app/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
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
