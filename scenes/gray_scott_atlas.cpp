// gs-atlas: a map of Gray-Scott patterns over a grid of (f, k), in the manner
// of Pearson (Science 1993): each tile is one run from the same start, its B
// drawn through Blues; f rises upwards, k to the right. It shows off the fast
// float kernel (sim/gray_scott_kernels): 576 runs of 128^2 cells x 10,000
// steps, of which 365 reach an exact fixed point early and stop there. The
// runs themselves are sim/gray_scott_atlas; the scene keeps only the tiles'
// float B (no double copies of 576 fields: on this VM each fresh page costs
// a fault) and summarises them on all threads.
#include "sim/gray_scott_atlas.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/tile_map.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"

namespace scenes {
namespace {

using A = sim::GrayScottAtlasParams;

// A [low, high] pair of rates, read into two members; the model checks their values.
Schema<A>::Read rate_range(double A::*low, double A::*high) {
    return [low, high](Settings& s, const std::string& key, A& atlas) {
        const std::vector<double> range = s.numbers(key, {atlas.*low, atlas.*high});
        if (range.size() != 2) s.refuse(key, "[lowest, highest]");
        atlas.*low = range[0];
        atlas.*high = range[1];
    };
}

const Schema<A> param_schema = [] {
    using G = sim::GrayScottParams;
    Schema<G> base;
    base.count("n", &G::n, "cells a side of each run");
    base.number("ra", &G::ra, "diffusion rate of A");
    base.number("rb", &G::rb, "diffusion rate of B");
    base.number("noise", &G::noise, "B starts uniform in [0, noise)");
    base.number("island", &G::island, "added to B on the central square");
    Schema<A> s;
    s.part(base, &A::base);
    s.count("steps", &A::steps, "steps of each run");
    s.key({"f_range", "[lowest, highest] feed rate, rows from bottom to top", "a list of numbers", "[lowest, highest]"},
          rate_range(&A::f_low, &A::f_high), [](const A& d) {
              return nlohmann::json({d.f_low, d.f_high});
          });
    s.key({"k_range", "[lowest, highest] kill rate, columns from left to right", "a list of numbers",
           "[lowest, highest]"},
          rate_range(&A::k_low, &A::k_high), [](const A& d) {
              return nlohmann::json({d.k_low, d.k_high});
          });
    s.key(
        {"tiles", "[columns, rows] of the map", "a list of integers", "[columns, rows]"},
        [](Settings& section, const std::string& key, A& atlas) {
            const std::vector<long long> tiles = section.integers(key, {atlas.columns, atlas.rows});
            if (tiles.size() != 2) section.refuse(key, "[columns, rows]");
            // Clamped only so that the model sees (and refuses) a count beyond an int.
            atlas.columns = static_cast<int>(std::clamp<long long>(tiles[0], INT_MIN, INT_MAX));
            atlas.rows = static_cast<int>(std::clamp<long long>(tiles[1], INT_MIN, INT_MAX));
        },
        [](const A& d) {
            return nlohmann::json({d.columns, d.rows});
        });
    s.check(validated<A>({{"columns", "tiles"}, {"rows", "tiles"}}));
    return s;
}();

A atlas_defaults() {
    A atlas;
    atlas.base.n = 128;
    return atlas;
}

const FieldSpec field_defaults{render::colormap("Blues"), {}, {}, 1.0f, render::Sampling::smooth, true, ""};

struct Style {
    FieldSpec field = field_defaults;
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>().part(field_spec_schema(), &Style::field).part(plot_settings_schema(), &Style::plot);

// The tile a stop's name gives back (a part's "stop"); `ran` for an unknown one is refused.
sim::TileStop tile_stop(const std::string& name) {
    for (sim::TileStop stop : {sim::TileStop::ran, sim::TileStop::b_gone, sim::TileStop::fixed_point})
        if (name == sim::to_string(stop)) return stop;
    throw std::runtime_error("a tile's result has an unknown stop '" + name + "'");
}

// Work items: one a tile, row-major from the top row, then the few tiles
// the float error is measured on, run again in double.
class GrayScottAtlasScene : public SceneBase, public WorkItems {
public:
    GrayScottAtlasScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(atlas_defaults()), style_schema.keys()),
          atlas_(param_schema.read(params_, atlas_defaults())),
          s_(style_schema.read(style_)),
          plot_(plot_style(s_.plot, options.scale)) {
        require_drawable(params_, "n", "each tile", atlas_.base.n, atlas_.base.n);
        // Its axes span the atlas's (k, f) ranges, known before any tile runs.
        require_text_fits(
            d, options, [&](const render::Rect& area) { return tile_map().text(area, plot_); }, plot_remedy);
    }

    // The starting A and B, each tile's B kept as floats and, while it is
    // drawn, its texture, and per thread a float kernel's padded A, B and
    // their next steps, and a tile's B as doubles to hash and to draw.
    std::vector<MemoryNeed> memory() const override {
        const int n = atlas_.base.n;
        const double tiles = double(atlas_.columns) * atlas_.rows;
        return {grid_need("grids of doubles", n, n, 8, 2.0),
                grid_need("tiles' B, kept as floats and drawn", n, n, 4 + field_layer_bytes_per_cell, tiles),
                grid_need("kernel grids of floats and a B of doubles", n + 2, n + 2, 4 * 4 + 8,
                          double(options_.threads)),
                grid_need("float error runs in double, each its kernel's grids and its B", n + 2, n + 2, 8 * 5,
                          double(sim::float_error_tiles(atlas_).size()))};
    }

    const WorkItems* work() const override { return this; }
    int item_count() const override { return tile_count() + int(sim::float_error_tiles(atlas_).size()); }
    std::string item_name(int item) const override {
        if (item < tile_count()) return "tile " + std::to_string(item);
        return "tile " + std::to_string(sim::float_error_tiles(atlas_)[item - tile_count()]) + " in double";
    }
    // A tile's B as floats, a tile in double's as doubles, and their keys.
    double item_bytes() const override { return 8.0 * atlas_.base.n * atlas_.base.n + 512; }
    double total_bytes() const override {
        const double cells = double(atlas_.base.n) * atlas_.base.n;
        return tile_count() * (4 * cells + 512) + double(sim::float_error_tiles(atlas_).size()) * item_bytes();
    }

    nlohmann::json run_item(int item) const override {
        const sim::GrayScott& begin = start();
        if (item < tile_count()) {
            const sim::GrayScottAtlasTile tile = sim::run_gray_scott_atlas_tile(atlas_, begin, item, "the run");
            return {{"f", tile.f},
                    {"k", tile.k},
                    {"stopped_at", tile.stopped_at},
                    {"stop", sim::to_string(tile.stop)},
                    {"b", binary_of<float>(tile.b.cells())}};
        }
        const int tile = sim::float_error_tiles(atlas_).at(static_cast<std::size_t>(item - tile_count()));
        return {{"tile", tile}, {"b", binary_of<double>(sim::gray_scott_atlas_double_b(atlas_, begin, tile).cells())}};
    }

    // A tile's rates are its index's, its B within the health bound every
    // finished run keeps; a tile in double is the one its index names.
    void check_result(int item, const nlohmann::json& r) const override {
        namespace rc = result_check;
        const std::size_t cells = static_cast<std::size_t>(atlas_.base.n) * atlas_.base.n;
        const double bound = sim::gray_scott_atlas_health_bound;
        if (item < tile_count()) {
            const auto [f, k] = sim::gray_scott_atlas_rates(atlas_, item);
            if (rc::member(r, "f") != f || rc::member(r, "k") != k)
                throw std::invalid_argument("its rates are not tile " + std::to_string(item) + "'s (f = " +
                                            rc::quoted(f) + ", k = " + rc::quoted(k) + ")");
            rc::integer_in(rc::member(r, "stopped_at"), "stopped_at", 0, atlas_.steps);
            rc::one_of(rc::member(r, "stop"), "stop", {"ran", "b_gone", "fixed_point"});
            rc::values_in<float>(rc::member(r, "b"), "b", cells, -bound, bound);
            return;
        }
        const int tile = sim::float_error_tiles(atlas_).at(static_cast<std::size_t>(item - tile_count()));
        if (rc::integer_in(rc::member(r, "tile"), "tile", 0, tile_count() - 1) != tile)
            throw std::invalid_argument("it is the double run of another tile than " + std::to_string(tile));
        rc::values_in<double>(rc::member(r, "b"), "b", cells, -bound, bound);
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, item_count());
        std::vector<nlohmann::json> results = out.results(*this);
        const std::vector<sim::GrayScottAtlasTile> tiles = decode_tiles(results);
        const std::vector<TileSummary> summaries = summarise(tiles);
        nlohmann::json tile_meta = nlohmann::json::array();
        int stopped = 0;
        for (std::size_t t = 0; t < tiles.size(); ++t) {
            const sim::GrayScottAtlasTile& tile = tiles[t];
            stopped += tile.stop != sim::TileStop::ran;
            tile_meta.push_back({{"f", tile.f},
                                 {"k", tile.k},
                                 {"mean_B", summaries[t].mean_b},
                                 {"state_sha256", summaries[t].state_sha256},
                                 {"stopped_at", tile.stopped_at},
                                 {"stop", sim::to_string(tile.stop)}});
        }
        const nlohmann::json early_stop = {
            {"rule", "a run stops once B is +0 in every cell (b_gone) or a step changes no bit of A or B "
                     "(fixed_point), tested every " + std::to_string(sim::gray_scott_atlas_stop_check) +
                         " steps: both leave B as the full run would"},
            {"tiles_stopped", stopped}};
        nlohmann::json meta = {{"params", params_.used()},
                               {"style", style_.used()},
                               {"early_stop", early_stop},
                               {"float_error", float_error(tiles, results)},
                               {"tiles", tile_meta}};
        if (const auto bar = colour_bar()) meta["colour_bar"] = colour_bar_metadata(*bar);  // as the deposit: only when drawn
        out.figure(draw_map(tiles, summaries), std::move(meta));
        progress.finish();
    }

private:
    int tile_count() const { return atlas_.columns * atlas_.rows; }

    // The start every tile runs from, made once, by whichever thread first needs it.
    const sim::GrayScott& start() const {
        std::call_once(start_made_, [&] { start_.emplace(sim::gray_scott_atlas_start(atlas_, d_.seed)); });
        return *start_;
    }

    // The tiles from their items' results, each result's B released as it is read.
    std::vector<sim::GrayScottAtlasTile> decode_tiles(std::vector<nlohmann::json>& results) const {
        const int n = atlas_.base.n;
        std::vector<sim::GrayScottAtlasTile> tiles(static_cast<std::size_t>(tile_count()));
        for (int t = 0; t < tile_count(); ++t) {
            nlohmann::json& r = results[static_cast<std::size_t>(t)];
            sim::GrayScottAtlasTile& tile = tiles[static_cast<std::size_t>(t)];
            tile.f = r.at("f").get<double>();
            tile.k = r.at("k").get<double>();
            tile.stopped_at = r.at("stopped_at").get<int>();
            tile.stop = tile_stop(r.at("stop").get<std::string>());
            const std::vector<float> b = values_of<float>(r.at("b"), static_cast<std::size_t>(n) * n);
            tile.b = sim::Grid<float>(n, n);
            std::copy(b.begin(), b.end(), tile.b.data());
            r = nullptr;
        }
        return tiles;
    }

    // The description asks for float32: what that costs, measured. A few
    // tiles ran again in double (the last work items).
    nlohmann::json float_error(const std::vector<sim::GrayScottAtlasTile>& tiles,
                               const std::vector<nlohmann::json>& results) const {
        const std::vector<int> which = sim::float_error_tiles(atlas_);
        const std::size_t cells = static_cast<std::size_t>(atlas_.base.n) * atlas_.base.n;
        std::vector<sim::FloatError> errors;
        for (std::size_t i = 0; i < which.size(); ++i) {
            const nlohmann::json& r = results[static_cast<std::size_t>(tile_count()) + i];
            errors.push_back(sim::float_error(tiles[which[i]], values_of<double>(r.at("b"), cells), which[i]));
        }
        nlohmann::json rows = nlohmann::json::array();
        double largest = 0;
        for (const sim::FloatError& e : errors) {
            rows.push_back({{"tile", e.tile}, {"f", e.f}, {"k", e.k}, {"max_abs_B", e.max_abs}, {"rms_B", e.rms}});
            largest = std::max(largest, e.max_abs);
        }
        return {{"against", "the same tiles run in double (every step, the double kernel)"},
                {"max_abs_B", largest},
                {"tiles", rows}};
    }

    // What the map and the metadata need of a tile's B.
    struct TileSummary {
        render::FieldStyle style;  // its colour range
        double mean_b = 0;
        std::string state_sha256;  // of B as doubles (exact copies of the floats)
        bool finite = true;
    };

    // Every tile's summary, the tiles spread over the OpenMP threads (each
    // hashes 128 KiB); then the first non-finite tile, if any, is refused.
    std::vector<TileSummary> summarise(const std::vector<sim::GrayScottAtlasTile>& tiles) const {
        std::vector<TileSummary> summaries(tiles.size());
        const long long count = static_cast<long long>(tiles.size());
#pragma omp parallel
        {
            std::vector<double> b;  // one tile's B as doubles, reused: no fresh pages a tile
#pragma omp for schedule(dynamic)
            for (long long t = 0; t < count; ++t) summaries[t] = summarise(tiles[t], b);
        }
        for (std::size_t t = 0; t < tiles.size(); ++t)
            if (!summaries[t].finite)
                throw std::runtime_error(d_.id + ": the run at f = " + format_fixed(tiles[t].f, 4) + ", k = " +
                                         format_fixed(tiles[t].k, 4) + " went numerically unstable; no image written");
        return summaries;
    }

    // One tile's summary; `b` is scratch space. Nothing here throws but
    // bad_alloc, which ends the program inside OpenMP as anywhere else.
    TileSummary summarise(const sim::GrayScottAtlasTile& tile, std::vector<double>& b) const {
        b.assign(tile.b.cells().begin(), tile.b.cells().end());
        TileSummary summary;
        double lo = b[0], hi = b[0], sum = 0;
        for (double v : b) {
            summary.finite &= std::isfinite(v);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            sum += v;  // in cell order, as the metadata has always summed
        }
        summary.mean_b = sum / double(b.size());
        summary.state_sha256 = state_hash(b);
        // The range as field_layer gives it (matplotlib maps an empty range
        // to the first colour). Where the spots die B freezes near 1e-37
        // (the float kernel flushes subnormals: f + k times B rounds to 0):
        // a tile whose B is below 1e-20 everywhere holds no chemical, and is
        // drawn flat, not as an autoscaled picture of rounding.
        double vmin = s_.field.vmin.value_or(lo), vmax = s_.field.vmax.value_or(hi);
        if (!(vmax > vmin) || (!s_.field.vmin && !s_.field.vmax && vmax < 1e-20)) vmax = vmin + 1;
        summary.style = {&s_.field.colormap, vmin, vmax, s_.field.alpha, s_.field.sampling};
        return summary;
    }

    // The tiles in a square plot frame, k along x and f up y, with the axes drawn over them.
    FigureDrawing draw_map(const std::vector<sim::GrayScottAtlasTile>& tiles,
                           const std::vector<TileSummary>& summaries) const {
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        return {width, height, false,
                [this, &tiles, &summaries](render::Surface& surface) { draw_map(surface, tiles, summaries); }};
    }

    void draw_map(render::Surface& canvas, const std::vector<sim::GrayScottAtlasTile>& tiles,
                  const std::vector<TileSummary>& summaries) const {
        tile_map().draw(canvas, plot_, [&](int t, std::vector<double>& b) {
            const sim::Grid<float>& cells = tiles[static_cast<std::size_t>(t)].b;
            b.assign(cells.cells().begin(), cells.cells().end());
            return TileMap::Tile{cells.rows(), cells.cols(), summaries[static_cast<std::size_t>(t)].style};
        });
    }

    TileMap tile_map() const { return {atlas_.columns, atlas_.rows, map_axes(), colour_bar()}; }

    // The axes drawn over the tiles: k along x, f up y.
    render::Axes map_axes() const {
        render::Axes axes;
        axes.x_range = std::pair{atlas_.k_low, atlas_.k_high};
        axes.y_range = std::pair{atlas_.f_low, atlas_.f_high};
        axes.x_label = "kill rate k";
        axes.y_label = "feed rate f";
        axes.title = "Gray-Scott B after " + std::to_string(atlas_.steps) + " steps, " +
                     std::to_string(atlas_.base.n) + "\u00b2 cells each";
        return axes;
    }

    // The colour bar, when [style] colour_bar: in B's units when vmin and vmax
    // fix one range for every tile; else each tile's own range, 0 to 1.
    std::optional<render::ColourBar> colour_bar() const {
        if (!s_.field.colour_bar) return std::nullopt;
        const std::string& label = s_.field.colour_bar_label;
        if (s_.field.vmin && s_.field.vmax)
            return render::ColourBar{s_.field.colormap, *s_.field.vmin, *s_.field.vmax, label.empty() ? "B" : label};
        return render::ColourBar{s_.field.colormap, 0.0, 1.0,
                                 label.empty() ? "B, each tile from its minimum (0) to its maximum (1)" : label};
    }

    const sim::GrayScottAtlasParams atlas_;
    mutable std::once_flag start_made_;
    mutable std::optional<sim::GrayScott> start_;
    const Style s_;
    const render::PlotStyle plot_;
};

std::unique_ptr<Scene> read_gray_scott_atlas(const Description& d, const SceneOptions& options) {
    return std::make_unique<GrayScottAtlasScene>(d, options);
}

}  // namespace

SceneInfo gray_scott_atlas_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"gray_scott_atlas",
            read_gray_scott_atlas,
            {"colormap"},
            {
                {"/tiles", "tiles", "count", ""},
                {"/early_stop/tiles_stopped", "tiles stopped early", "integer", ""},
                {"/float_error/max_abs_B", "largest float error in B", "number", "", {}, "", "", 2},
            }};
}

}  // namespace scenes
