// Iterated function systems ("Plants hidden in mathematical formulas", part
// 3): the chaos game's points binned into the panel's pixels, drawn as a
// density (log of the count through a colormap) or as plain points.
#include <cmath>

#include "figures/field_spec.hpp"
#include "figures/field_stats.hpp"
#include "figures/scene.hpp"
#include "sim/check.hpp"
#include "sim/ifs.hpp"
#include "sim/random.hpp"

namespace figures {
namespace {

// [[a, b, c, d, e, f, p], ...] from a variant's table.
sim::Ifs read_maps(const toml::table& variant, const std::string& where) {
    const toml::array* maps = variant["maps"].as_array();
    if (!maps) throw UsageError(where + ".maps: expected a list of [a, b, c, d, e, f, p]");
    sim::Ifs ifs;
    for (const toml::node& row : *maps) {
        const toml::array* values = row.as_array();
        if (!values || values->size() != 7)
            throw UsageError(where + ".maps: each map is [a, b, c, d, e, f, p], seven numbers");
        double v[7];
        for (std::size_t i = 0; i < 7; ++i) {
            const auto number = (*values)[i].value<double>();
            if (!number) throw UsageError(where + ".maps: each map is [a, b, c, d, e, f, p], seven numbers");
            v[i] = *number;
        }
        ifs.maps.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
    }
    return ifs;
}

// SHA-256 of the points' x and y, in the order the game made them.
std::string points_hash(const std::vector<glm::dvec2>& points) {
    std::vector<double> xy;
    xy.reserve(2 * points.size());
    for (const auto& p : points) xy.insert(xy.end(), {p.x, p.y});
    return state_hash(xy);
}

}  // namespace

void render_ifs(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"variants", "list of {title, maps = [[a, b, c, d, e, f, p], ...]}, one panel each"},
                     {"points", "points per panel"},
                     {"discard", "first points dropped"},
                     {"bounds", "[xmin, xmax, ymin, ymax] drawn; absent: the points' own bounds"}});
    auto keys = field_spec_keys();
    keys.push_back({"mode", "\"density\" (log count through the colormap) or \"points\""});
    Settings style("style", d.style, keys);
    const auto variants = params.tables("variants");
    if (variants.empty()) throw UsageError(d.id + ": params.variants is empty");
    sim::ChaosGameParams game;
    std::vector<double> bounds;
    try {
        game.points = static_cast<std::uint64_t>(std::max(0LL, params.integer("points", 200000)));
        game.discard = static_cast<std::uint64_t>(std::max(0LL, params.integer("discard", 100)));
        sim::require_integer("points", params.integer("points", 200000), 1, 20'000'000);
        sim::require_integer("discard", params.integer("discard", 100), 0, 100'000'000);
        game.validate();
        bounds = params.numbers("bounds", {});
        if (!bounds.empty() && (bounds.size() != 4 || !(bounds[1] > bounds[0]) || !(bounds[3] > bounds[2])))
            throw UsageError(d.id + ": params.bounds must be [xmin, xmax, ymin, ymax] with min < max");
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const std::string mode = style.text("mode", "density");
    if (mode != "density" && mode != "points")
        throw UsageError(d.id + ": style.mode = \"" + mode + "\" is not allowed: use \"density\" or \"points\"");
    const FieldSpec spec =
        read_field_spec(style, {render::colormap("Greens"), 0.0, {}, 1.0f, render::Sampling::nearest});
    progress.start(d.id, static_cast<long long>(variants.size()));

    // Every panel's points, two doubles each, kept until the figure is drawn.
    require_memory(d, options,
                   {{std::to_string(variants.size()) + " x " + std::to_string(game.points) + " points",
                     16.0 * double(game.points) * double(variants.size())}});
    sim::Random rng(d.seed);  // one stream for all panels, in order
    std::vector<sim::Ifs> systems;
    std::vector<std::string> titles;
    std::vector<std::vector<glm::dvec2>> clouds;
    nlohmann::json panel_meta = nlohmann::json::array();
    glm::dvec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const std::string where = "params.variants[" + std::to_string(i) + "]";
        sim::Ifs ifs = read_maps(variants[i], where);
        try {
            ifs.validate();
        } catch (const std::invalid_argument& e) {
            throw UsageError(d.id + ": " + where + ": " + e.what());
        }
        std::vector<std::uint64_t> counts;
        clouds.push_back(sim::chaos_game(ifs, game, rng, &counts));
        glm::dvec2 own_lo{1e300, 1e300}, own_hi{-1e300, -1e300};
        for (const auto& p : clouds.back()) {
            own_lo = glm::min(own_lo, p);
            own_hi = glm::max(own_hi, p);
        }
        lo = glm::min(lo, own_lo);
        hi = glm::max(hi, own_hi);
        titles.push_back(variants[i]["title"].value_or(std::string()));
        nlohmann::json maps = nlohmann::json::array();
        for (const auto& m : ifs.maps) maps.push_back({m.a, m.b, m.c, m.d, m.e, m.f, m.p});
        panel_meta.push_back({{"title", titles.back()},
                              {"maps", maps},
                              {"points", clouds.back().size()},
                              {"map_counts", counts},
                              {"points_bounds", {own_lo.x, own_hi.x, own_lo.y, own_hi.y}},
                              {"state_sha256", points_hash(clouds.back())}});
        progress.advance();
    }
    if (!bounds.empty()) {
        lo = {bounds[0], bounds[2]};
        hi = {bounds[1], bounds[3]};
    }

    // Each panel bins its points into as many cells as the panel has pixels.
    const int width = figure_width(d, options), height = figure_height(d, options);
    render::PanelRowStyle row;
    row.scale = float(options.scale);
    row.aspect = float((hi.x - lo.x) / (hi.y - lo.y));
    const auto rects = render::panel_row(width, height, int(clouds.size()), true, row);
    std::vector<FieldPanel> panels;
    // One spec per panel, alive until drawn: a field layer points at its colormap.
    std::vector<FieldSpec> specs(clouds.size(), spec);
    for (std::size_t i = 0; i < clouds.size(); ++i) {
        const int cols = std::max(1, int(rects[i].w)), rows = std::max(1, int(rects[i].h));
        const sim::Density density = sim::density(clouds[i], cols, rows, lo, hi);
        sim::Grid<double> field(rows, cols);
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c) {
                const double n = density.at(r, c);
                field(r, c) = mode == "points" ? (n > 0 ? 1.0 : 0.0) : std::log1p(n);
            }
        if (mode == "points") specs[i].colormap = render::listed_colormap("points", {{1, 1, 1}, {0.0f, 0.45f, 0.1f}});
        panels.push_back({titles[i], {field_layer(field, specs[i])}});
        panel_meta[i]["drawn_bounds"] = {lo.x, hi.x, lo.y, hi.y};
    }
    write_figure(d, options, draw_field_panels(panels, width, height, options.scale),
                 {{"params", params.used()}, {"style", style.used()}, {"panels", panel_meta}});
    progress.finish();
}

}  // namespace figures
