// An atlas of any formula model (scene = "formula_atlas"): two of the
// rule's parameters swept over a grid of tiles, each tile its own run of
// the model from the same start, one chemical of each drawn at its last
// step, as gs-atlas maps Gray-Scott over (f, k). [params] is the formula
// scene's (scenes/helpers/formula_model.hpp) and x_parameter, x_range, y_parameter,
// y_range, tiles; the swept parameters get each tile's values (tile
// centres: the first column at x_lo + half a tile), x to the right, y up.
//
// A tile shows what a person looks at in a run of its grid's dimension:
// on a 2-D grid the chemical at the last step; on a 1-D grid (height and
// depth 1) its space-time diagram, x across and the steps down (at most
// atlas_space_time_rows rows, every stride-th step and the last); on a 3-D
// grid the plane through the centre (z = depth / 2) at the last step, as
// the formula figure's slices. Each tile's state_sha256 is its whole
// chemical at the last step, as the formula figure hashes it.
//
// Each tile is a work item: threads, MPI ranks, shards and resume as for
// gs-atlas. A tile whose run goes unstable (a division by zero, a chemical
// no longer finite) is a result too: drawn grey and named in the metadata.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "render/colormap.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/formula_model.hpp"
#include "scenes/helpers/panel_grid.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/tile_map.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_codec.hpp"
#include "scenes/work_items.hpp"
#include "sim/formula/names.hpp"

namespace scenes {
namespace {

namespace formula = sim::formula;

struct Sweep {
    std::string x, y;  // the parameters
    double x_low = 0, x_high = 1, y_low = 0, y_high = 1;
    int columns = 8, rows = 8;
};

const char* const parameter_allowed = "the name of a parameter the formula uses (not timestep or dx)";

// A swept parameter's name; whether the formula uses it is checked once the
// formula itself has been.
Schema<Sweep>::Read parameter_name(std::string Sweep::*member) {
    return [member](Settings& s, const std::string& key, Sweep& w) {
        const std::string name = s.text(key, w.*member);
        bool plain = !name.empty() && name.size() <= 64 && !std::isdigit(static_cast<unsigned char>(name[0]));
        for (char c : name) plain &= std::isalnum(static_cast<unsigned char>(c)) || c == '_';
        if (!plain || name == "timestep" || name == "dx") s.refuse(key, parameter_allowed);
        w.*member = name;
    };
}

Schema<Sweep>::Read parameter_range(double Sweep::*low, double Sweep::*high) {
    return [low, high](Settings& s, const std::string& key, Sweep& w) {
        const std::vector<double> r = s.numbers(key, {w.*low, w.*high});
        if (r.size() != 2 || !std::isfinite(r[0]) || !std::isfinite(r[1]) || !(r[1] > r[0]) ||
            std::fabs(r[0]) > 1e30 || std::fabs(r[1]) > 1e30)
            s.refuse(key, "[lowest, highest]: two finite numbers, the second greater");
        w.*low = r[0];
        w.*high = r[1];
    };
}

const std::string range_allowed = "[lowest, highest]: two finite numbers, the second greater";

const Schema<Sweep> sweep_schema =
    Schema<Sweep>()
        .key({"x_parameter", "the rule's parameter swept across, left to right", "text", parameter_allowed},
             parameter_name(&Sweep::x))
        .key({"x_range", "[lowest, highest] of x_parameter, the tiles' centres spread over it", "a list of numbers",
              range_allowed, nlohmann::json({0, 1})},
             parameter_range(&Sweep::x_low, &Sweep::x_high))
        .key({"y_parameter", "the rule's parameter swept up, bottom to top", "text",
              std::string(parameter_allowed) + ", other than x_parameter"},
             parameter_name(&Sweep::y))
        .key(
            {"y_range", "[lowest, highest] of y_parameter", "a list of numbers", range_allowed, nlohmann::json({0, 1})},
            parameter_range(&Sweep::y_low, &Sweep::y_high))
        .key({"tiles", "[columns, rows] of the map", "a list of integers",
              "[columns, rows], each an integer from 1 to 64", nlohmann::json({8, 8})},
             [](Settings& s, const std::string& key, Sweep& w) {
                 const std::vector<long long> tiles = s.integers(key, {w.columns, w.rows});
                 if (tiles.size() != 2 || tiles[0] < 1 || tiles[0] > 64 || tiles[1] < 1 || tiles[1] > 64)
                     s.refuse(key, "[columns, rows], each an integer from 1 to 64");
                 w.columns = static_cast<int>(tiles[0]);
                 w.rows = static_cast<int>(tiles[1]);
             })
        .check([](Settings& s, const std::string&, Sweep& w) {
            if (w.x == w.y) s.refuse("y_parameter", "a parameter other than x_parameter (" + w.x + ")");
        });

struct Style {
    std::string show = "a";
    int shown = 0;
    bool each_tile = false;  // tile_range = "each"
    FieldSpec field{render::colormap("viridis"), {}, {}, 1.0f, render::Sampling::smooth, true, ""};
    PlotSettings plot;
};

// The rule's chemicals as the description gives them: `show` names one.
Schema<Style> style_schema(int chemicals) {
    return Schema<Style>()
        .key({"show", "the chemical each tile shows, e.g. \"b\"", "text", "a chemical of the rule", "a"},
             [chemicals](Settings& s, const std::string& key, Style& v) {
                 v.show = s.text(key, v.show);
                 v.shown = chemical_index(s, key, v.show, chemicals);
             })
        .choice("tile_range", &Style::each_tile, {{"all", false}, {"each", true}},
                "without vmin and vmax, the colours span all the tiles' values (one range) or each tile's own")
        .part(field_spec_schema(), &Style::field)
        .part(plot_settings_schema(), &Style::plot);
}

// The tile's parameter values: at the tiles' centres, y rising up the rows
// (row 0 is the top).
std::pair<double, double> tile_values(const Sweep& w, int tile) {
    const int r = tile / w.columns, c = tile % w.columns;
    const double x = w.x_low + (c + 0.5) / w.columns * (w.x_high - w.x_low);
    const double y = w.y_low + (w.rows - r - 0.5) / w.rows * (w.y_high - w.y_low);
    return {x, y};
}

class FormulaAtlasScene : public SceneBase, public WorkItems {
public:
    FormulaAtlasScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, formula_param_keys(d, sweep_schema.keys()), style_schema(formula_chemicals(d)).keys()),
          sweep_(sweep_schema.read(params_)),
          m_(read_formula_model(params_, d, sweep_schema.keys(), {{sweep_.x, sweep_.x_low}, {sweep_.y, sweep_.y_low}})),
          s_(style_schema(m_.rule.chemicals).read(style_)),
          plot_(plot_style(s_.plot, options.scale)) {
        const std::set<std::string> words = formula_names(params_, m_.rule.code);
        for (const auto& [key, name] : {std::pair{"x_parameter", sweep_.x}, std::pair{"y_parameter", sweep_.y}}) {
            if (const auto clash = sim::formula::parameter_name_clash(name, m_.rule.chemicals))
                params_.refuse(key, "its name is " + *clash + "; " + sim::formula::parameter_name_allowed);
            if (!words.count(name)) params_.refuse(key, parameter_allowed);
        }
        // A grid of x and z alone has no view here: 1-D grids are a row, 3-D ones have a height.
        if (m_.height == 1 && m_.depth > 1)
            params_.refuse("height", integers_allowed(2, formula_most_side) +
                                         " with depth > 1 (a 1-D grid has height 1 and depth 1)");
        require_drawable(params_, "width", "each tile", m_.height, m_.width);
        require_text_fits(
            d, options, [&](const render::Rect& area) { return tile_map().text(area, plot_); }, plot_remedy);
    }

    // Per thread a run's chemicals (two states, three on a 2-D grid; rows
    // with halos) and its
    // registers; the start; every tile's chemical kept (float or double)
    // and, while drawn, as doubles with a texture.
    std::vector<MemoryNeed> memory() const override {
        const double cell = m_.rule.double_precision ? 8 : 4, chemicals = m_.rule.chemicals;
        const double row = m_.width + 2.0 * m_.radius_x + 64 / cell;
        const double threads = std::max(1, options_.threads);
        return {grid_need("the arrays a Ready pattern stores", m_.height, m_.width, 8, d_.stored_start ? chemicals : 0),
                grid_need("each thread's run: chemicals",
                          static_cast<double>(m_.height) * m_.depth + formula_ghost_rows(m_) + 3, row, cell,
                          sim::formula::state_copies(m_.height, m_.depth, m_.rule.integrator) * chemicals * threads),
                grid_need("each thread's run: registers", threads * (m_.registers + 1), sim::formula::chunk_lanes + 64 / cell, cell, 1),
                grid_need("each thread's run: machine code", threads, m_.machine_code, 1, 1),
                grid_need("the start", static_cast<double>(m_.height) * m_.depth, m_.width, 8, chemicals),
                grid_need("each thread's chemical read at the end", static_cast<double>(m_.height) * m_.depth,
                          m_.width, 8, threads),
                grid_need("the tiles kept", tile_rows(), m_.width, cell + 8 + field_layer_bytes_per_cell, tile_count())};
    }

    const WorkItems* work() const override { return this; }
    int item_count() const override { return tile_count(); }
    std::string item_name(int item) const override {
        const auto [x, y] = tile_values(sweep_, item);
        return "tile " + std::to_string(item) + " (" + sweep_.x + " = " + description::shown(x) + ", " + sweep_.y +
               " = " + description::shown(y) + ")";
    }
    double item_bytes() const override { return (m_.rule.double_precision ? 8.0 : 4.0) * m_.width * tile_rows() + 1024; }

    nlohmann::json run_item(int item) const override {
        const auto [x, y] = tile_values(sweep_, item);
        formula::Rule rule = m_.rule;
        for (auto& [name, value] : rule.parameters) {
            if (name == sweep_.x) value = x;
            if (name == sweep_.y) value = y;
        }
        nlohmann::json r = {{"x", x}, {"y", y}};
        try {
            formula::Run run(rule, m_.width, m_.height, m_.depth, start());
            // One thread a tile: the tiles run side by side.
            std::vector<double> shown;
            if (dimensions_ == 1) {
                // The space-time diagram: the row at step 0, every stride-th step and the last.
                const int stride = space_time_stride();
                for (int step = 0;; step = std::min(m_.steps, step + stride)) {
                    if (step > run.steps()) run.step(step - static_cast<int>(run.steps()), 1);
                    const sim::Grid<double> g = run.chemical(s_.shown);
                    shown.insert(shown.end(), g.cells().begin(), g.cells().end());
                    if (step == m_.steps) break;
                }
            } else {
                run.step(m_.steps, 1);
                const sim::Grid<double> g = run.chemical(s_.shown);
                if (dimensions_ == 3) {
                    // The centre plane, and the whole chemical's hash and mean.
                    const std::size_t plane = static_cast<std::size_t>(m_.width) * m_.height;
                    const auto from = g.cells().begin() + static_cast<std::ptrdiff_t>(plane * (m_.depth / 2));
                    shown.assign(from, from + static_cast<std::ptrdiff_t>(plane));
                    double sum = 0;
                    for (double v : g.cells()) sum += v;
                    r["mean"] = sum / static_cast<double>(g.cells().size());
                    r["state_sha256"] = state_hash(g);
                } else {
                    shown.assign(g.cells().begin(), g.cells().end());
                }
            }
            if (m_.rule.double_precision) {
                r["values"] = binary_of<double>(std::span<const double>(shown));
            } else {
                const std::vector<float> f(shown.begin(), shown.end());
                r["values"] = binary_of<float>(std::span<const float>(f));
            }
        } catch (const formula::Unstable& e) {
            r["unstable"] = e.what();
        }
        return r;
    }

    void check_result(int item, const nlohmann::json& r) const override {
        namespace rc = result_check;
        const auto [x, y] = tile_values(sweep_, item);
        if (rc::member(r, "x") != x || rc::member(r, "y") != y)
            throw std::invalid_argument("its parameters are not tile " + std::to_string(item) + "'s");
        if (r.contains("unstable")) {
            if (!r["unstable"].is_string()) throw std::invalid_argument("unstable is not a text");
            return;
        }
        if (dimensions_ == 3) {
            const nlohmann::json& hash = rc::member(r, "state_sha256");
            if (!hash.is_string() || hash.get_ref<const std::string&>().size() != 64 ||
                hash.get_ref<const std::string&>().find_first_not_of("0123456789abcdef") != std::string::npos)
                throw std::invalid_argument("its state_sha256 is not 64 hexadecimal digits");
            const nlohmann::json& mean = rc::member(r, "mean");
            if (!mean.is_number() || !std::isfinite(mean.get<double>()))
                throw std::invalid_argument("its mean is not a finite number");
        }
        const std::size_t cells = static_cast<std::size_t>(m_.width) * tile_rows();
        if (m_.rule.double_precision) rc::values_in<double>(rc::member(r, "values"), "values", cells, -1e300, 1e300);
        else rc::values_in<float>(rc::member(r, "values"), "values", cells, -3.4e38, 3.4e38);
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, item_count());
        std::vector<nlohmann::json> results = out.results(*this);
        tiles_.assign(static_cast<std::size_t>(tile_count()), {});
        nlohmann::json tile_meta = nlohmann::json::array();
        int unstable = 0;
        for (int t = 0; t < tile_count(); ++t) {
            nlohmann::json& r = results[static_cast<std::size_t>(t)];
            Tile& tile = tiles_[static_cast<std::size_t>(t)];
            nlohmann::json meta = {{sweep_.x, r.at("x")}, {sweep_.y, r.at("y")}};
            if (r.contains("unstable")) {
                ++unstable;
                meta["unstable"] = r["unstable"];
            } else {
                const std::size_t cells = static_cast<std::size_t>(m_.width) * tile_rows();
                if (m_.rule.double_precision) {
                    tile.values = values_of<double>(r.at("values"), cells);
                } else {
                    const auto f = values_of<float>(r.at("values"), cells);
                    tile.values.assign(f.begin(), f.end());
                }
                if (dimensions_ == 3) {
                    meta["mean"] = r.at("mean");
                    meta["state_sha256"] = r.at("state_sha256");
                } else {
                    // The chemical at the last step: the tile, or a 1-D diagram's last row.
                    const std::vector<double> last(tile.values.end() - static_cast<std::ptrdiff_t>(m_.width) *
                                                                           (dimensions_ == 1 ? 1 : m_.height),
                                                   tile.values.end());
                    double sum = 0;
                    for (double v : last) sum += v;
                    meta["mean"] = sum / static_cast<double>(last.size());
                    meta["state_sha256"] = state_hash(last);  // as the formula scene hashes a chemical
                }
                // Drawn with y = 0 at the bottom, as the formula scene draws;
                // a space-time diagram's steps run down from the top.
                const int rows = dimensions_ == 1 ? 0 : m_.height;
                for (int row = 0; row < rows / 2; ++row)
                    std::swap_ranges(tile.values.begin() + static_cast<std::ptrdiff_t>(row) * m_.width,
                                     tile.values.begin() + static_cast<std::ptrdiff_t>(row + 1) * m_.width,
                                     tile.values.begin() + static_cast<std::ptrdiff_t>(m_.height - 1 - row) * m_.width);
            }
            r = nullptr;
            tile_meta.push_back(std::move(meta));
        }
        // The colour range: vmin and vmax, else every tile's values (or each its own).
        double all_lo = 0, all_hi = 0;
        bool any = false;
        for (const Tile& tile : tiles_)
            if (!tile.values.empty()) {
                const auto [lo, hi] = std::minmax_element(tile.values.begin(), tile.values.end());
                all_lo = any ? std::min(all_lo, *lo) : *lo;
                all_hi = any ? std::max(all_hi, *hi) : *hi;
                any = true;
            }
        for (Tile& tile : tiles_) {
            if (tile.values.empty()) continue;
            double lo = all_lo, hi = all_hi;
            if (s_.each_tile) {
                const auto [l, h] = std::minmax_element(tile.values.begin(), tile.values.end());
                lo = *l;
                hi = *h;
            }
            double vmin = s_.field.vmin.value_or(lo), vmax = s_.field.vmax.value_or(hi);
            if (!(vmax > vmin)) vmax = vmin + 1;
            tile.style = {&s_.field.colormap, vmin, vmax, s_.field.alpha, s_.field.sampling};
        }
        range_ = {all_lo, any && all_hi > all_lo ? all_hi : all_lo + 1};
        nlohmann::json meta = {
            {"params", params_.used()},   {"style", style_.used()}, {"shows", formula::chemical_name(s_.shown)},
            {"tiles_unstable", unstable}, {"tiles", tile_meta},     {"model_operations", m_.operations}};
        if (dimensions_ == 1)
            meta["tile_shows"] = {{"view", "space-time diagram"}, {"rows", tile_rows()}, {"stride", space_time_stride()}};
        if (dimensions_ == 3) meta["tile_shows"] = {{"view", "plane"}, {"z", m_.depth / 2}};
        if (const auto bar = colour_bar()) meta["colour_bar"] = colour_bar_metadata(*bar);
        const int width = figure_width(d_, options_), height = figure_height(d_, options_);
        out.figure({width, height, false, [this](render::Surface& s) { draw(s); }}, std::move(meta));
        progress.finish();
    }

private:
    struct Tile {
        std::vector<double> values;  // empty: the run went unstable
        render::FieldStyle style;
    };

    int tile_count() const { return sweep_.columns * sweep_.rows; }

    // A 1-D tile's space-time diagram: the row at step 0, then every
    // stride-th step and the last, at most atlas_space_time_rows + 1 rows.
    static constexpr int atlas_space_time_rows = 128;
    int space_time_stride() const { return scenes::space_time_stride(m_.steps, atlas_space_time_rows); }
    // The rows a tile shows: the diagram's, or a plane's.
    int tile_rows() const {
        if (dimensions_ != 1) return m_.height;
        const int stride = space_time_stride();
        return (m_.steps + stride - 1) / stride + 1;
    }

    const std::vector<sim::Grid<double>>& start() const {
        std::call_once(start_made_, [&] { start_ = formula_start(m_, d_); });
        return start_;
    }

    void draw(render::Surface& surface) const {
        static const render::Colormap grey = render::listed_colormap("unstable", {{0.6f, 0.6f, 0.6f}});
        tile_map().draw(surface, plot_, [&](int t, std::vector<double>& values) {
            const Tile& tile = tiles_[static_cast<std::size_t>(t)];
            if (tile.values.empty()) {
                values.assign(1, 0.0);
                return TileMap::Tile{1, 1, {&grey, 0, 1, 1.0f, render::Sampling::nearest}};
            }
            values = tile.values;
            return TileMap::Tile{tile_rows(), m_.width, tile.style};
        });
    }

    TileMap tile_map() const {
        render::Axes axes;
        axes.x_range = std::pair{sweep_.x_low, sweep_.x_high};
        axes.y_range = std::pair{sweep_.y_low, sweep_.y_high};
        axes.x_label = sweep_.x;
        axes.y_label = sweep_.y;
        axes.title = d_.title;
        return {sweep_.columns, sweep_.rows, axes, colour_bar()};
    }

    std::optional<render::ColourBar> colour_bar() const {
        if (!s_.field.colour_bar) return std::nullopt;
        const std::string chem = formula::chemical_name(s_.shown);
        const std::string& label = s_.field.colour_bar_label;
        if (s_.field.vmin && s_.field.vmax)
            return render::ColourBar{s_.field.colormap, *s_.field.vmin, *s_.field.vmax, label.empty() ? chem : label};
        if (!s_.each_tile)
            return render::ColourBar{s_.field.colormap, s_.field.vmin.value_or(range_.first),
                                     s_.field.vmax.value_or(range_.second), label.empty() ? chem : label};
        return render::ColourBar{s_.field.colormap, 0.0, 1.0,
                                 label.empty() ? chem + ", each tile from its minimum (0) to its maximum (1)" : label};
    }

    const Sweep sweep_;
    const FormulaModel m_;
    const int dimensions_ = formula::dimensionality(m_.width, m_.height, m_.depth);
    const Style s_;
    const render::PlotStyle plot_;
    mutable std::once_flag start_made_;
    mutable std::vector<sim::Grid<double>> start_;
    mutable std::vector<Tile> tiles_;
    mutable std::pair<double, double> range_{0.0, 1.0};  // every tile's values, once the tiles ran
};

std::unique_ptr<Scene> read_formula_atlas(const Description& d, const SceneOptions& options) {
    return std::make_unique<FormulaAtlasScene>(d, options);
}

}  // namespace

SceneInfo formula_atlas_scene() {
    return {"formula_atlas", read_formula_atlas, {"colormap"}};
}

}  // namespace scenes
