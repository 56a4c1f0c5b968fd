// Ballistic deposition ("Ballistic deposition in Python"): the deposit of
// L^2 particles coloured by arrival time in bands, and its growth as a film.
#include "sim/deposition.hpp"

#include <algorithm>

#include "base/digest.hpp"
#include "render/colormap.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/model_check.hpp"
#include "scenes/helpers/step_runner.hpp"
#include "scenes/scene.hpp"

namespace scenes {
namespace {

using P = sim::DepositionParams;
const Schema<P> param_schema =
    Schema<P>()
        .count("width", &P::width, "columns L (periodic)")
        .count("particles", &P::particles, "particles dropped; the catalog: L^2", 1, 50'000'000)
        .check(validated<P>());

struct Style {
    int bands = 20;
    std::string band_colormap = "viridis";
    bool colour_bar = true;
    std::string colour_bar_label = "arrival time (monolayers)";
    FieldSpec spec;  // white for empty cells, then the bands alternating light and dark along the ramp
};

const Schema<Style> style_schema = Schema<Style>()
                                       .count("bands", &Style::bands, "arrival-time bands, coloured in turn", 1, 255)
                                       .key(
                                           {"band_colormap", "colormap the bands run through", "text"},
                                           [](Settings& style, const std::string& key, Style& s) {
                                               s.band_colormap = style.text(key, s.band_colormap);
                                               const render::Colormap* ramp = render::find_colormap(s.band_colormap);
                                               if (!ramp) {
                                                   std::string allowed;
                                                   for (const auto& name : render::colormap_names())
                                                       allowed += (allowed.empty() ? "" : ", ") + name;
                                                   style.refuse(key, "one of " + allowed);
                                               }
                                               std::vector<glm::vec3> colours = {{1, 1, 1}};
                                               for (int b = 0; b < s.bands; ++b) {
                                                   const glm::vec3 c = ramp->at((b + 0.5) / s.bands);
                                                   colours.push_back(b % 2 ? glm::mix(c, glm::vec3(1), 0.35f) : c);
                                               }
                                               s.spec = {render::listed_colormap("bands", colours), 0.0,
                                                         double(s.bands), 1.0f, render::Sampling::nearest};
                                           },
                                           [](const Style& d) { return nlohmann::json(d.band_colormap); })
                                       .flag("colour_bar", &Style::colour_bar,
                                             "the bands' colour bar beside the deposit, in monolayers of arrival time")
                                       .text("colour_bar_label", &Style::colour_bar_label, "the colour bar's label");

// The deposit as a field: 0 empty, band + 1 for a particle of that arrival band.
sim::Grid<double> deposit_field(const sim::Deposition& deposit, int rows, std::uint64_t band_size) {
    const int width = deposit.params().width;
    sim::Grid<double> field(rows, width, 0.0);
    for (const auto& p : deposit.particles())
        if (p.height <= rows) field(rows - int(p.height), p.column) = double(p.arrival / band_size + 1);
    return field;
}

// SHA-256 of every particle's column, height and arrival (as 64-bit
// integers), in arrival order: the deposit the picture is drawn from.
std::string deposit_hash(const sim::Deposition& deposit) {
    std::vector<std::int64_t> flat;
    for (const auto& p : deposit.particles())
        flat.insert(flat.end(), {std::int64_t(p.column), p.height, std::int64_t(p.arrival)});
    return base::sha256_hex(flat.data(), flat.size() * sizeof(std::int64_t));
}

std::int64_t max_height(const sim::Deposition& deposit) {
    std::int64_t top = 0;
    for (auto h : deposit.heights()) top = std::max(top, h);
    return top;
}

// The film's field over the view's rows, kept up to date particle by
// particle: a drop raises exactly one column, so comparing heights finds
// where it landed.
class FilmField {
public:
    FilmField(const sim::Deposition& deposit, int rows, std::uint64_t band_size)
        : rows_(rows), band_size_(band_size), field_(rows, deposit.params().width, 0.0), before_(deposit.heights()) {}

    void drop_one(sim::Deposition& deposit) {
        deposit.drop();
        const auto& after = deposit.heights();
        for (int c = 0; c < deposit.params().width; ++c)
            if (after[c] != before_[c]) {
                if (after[c] <= rows_)
                    field_(rows_ - int(after[c]), c) = double((deposit.dropped() - 1) / band_size_ + 1);
                before_[c] = after[c];
                break;
            }
    }
    const sim::Grid<double>& field() const { return field_; }

private:
    int rows_;
    std::uint64_t band_size_;
    sim::Grid<double> field_;
    std::vector<std::int64_t> before_;
};

class DepositionScene : public SceneBase {
public:
    DepositionScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          band_size_((p_.particles + s_.bands - 1) / std::uint64_t(s_.bands)),
          // Steps of the film are monolayers (L particles); the view is tall
          // enough for the last one: ballistic deposits fill about half their cells.
          monolayers_(int((p_.particles + p_.width - 1) / p_.width)),
          view_rows_(int(2.4 * monolayers_) + 16),
          plan_(d) {
        plan_.panels = {monolayers_};
        // The view is tall when there are many particles a column, wide when there are many columns.
        require_drawable(params_, view_rows_ >= p_.width ? "particles" : "width", "the deposit's view", view_rows_,
                         p_.width);
    }

    // The deposit's cells (bytes) and the film's field (doubles) over the
    // view; each particle in its column (a doubling vector: twice its 8
    // bytes at most), in the list of particles the figure reads and that
    // list's growth (24 twice), and 32 more measured: 1M and 3M particles on
    // 500 columns peaked at 227.3 and 439.6 MiB, 84 bytes a particle beside
    // the view.
    std::vector<MemoryNeed> memory() const override {
        return {grid_need("cells of a byte and a double", view_rows_, p_.width, 9, 1),
                {std::to_string(p_.particles) + " particles", double(p_.particles) * (2 * 8 + 2 * 24 + 32)}};
    }

    void render(Output& out) const override {
        sim::Deposition deposit(p_, d_.seed);
        FilmField film(deposit, view_rows_, band_size_);
        StepRunner run(plan_, options_, out);
        run.run(
            {.check = {},
             .panel = {},
             .frame = [&](int step) -> FrameDrawing {
                 return run.field_frame(
                     {{format_step(d_.animation->title, step), {field_layer(film.field(), s_.spec, Cells::viewed)}}});
             },
             .advance =
                 [&] {
                     const std::uint64_t left = p_.particles - deposit.dropped();
                     for (std::uint64_t k = 0, n = std::min<std::uint64_t>(left, std::uint64_t(p_.width)); k < n; ++k)
                         film.drop_one(deposit);
                     return true;
                 }});
        if (run.film_only()) return run.finish_film();  // a film segment's run: no figure
        const std::int64_t top = max_height(deposit);
        const auto field = deposit_field(deposit, int(top) + 2, band_size_);
        std::vector<FieldPanel> panels = {{d_.panel_title, {field_layer(field, s_.spec)}}};
        if (s_.colour_bar) panels[0].layers[0].colour_bar = band_bar();
        run.write_figure(field_figure(panels, d_, options_),
                         metadata(deposit, top));
    }

private:
    nlohmann::json metadata(const sim::Deposition& deposit, std::int64_t top) const {
        nlohmann::json meta = {
            {"params", params_.used()},
            {"style", style_.used()},
            {"panels",
             {{{"particles", deposit.dropped()},
               {"cells", deposit.cells()},
               {"statistics",
                {{"mean_height", deposit.mean_height()}, {"roughness", deposit.roughness()}, {"max_height", top}}},
               {"packing_fraction", double(deposit.cells()) / (double(p_.width) * deposit.mean_height())},
               {"band_particles", band_size_},
               {"state_sha256", deposit_hash(deposit)}}}},
        };
        if (s_.colour_bar) meta["colour_bar"] = colour_bar_metadata(band_bar());
        return meta;
    }

    const sim::DepositionParams p_;
    // The bands' colours (the field's colormap without its white for empty
    // cells) over the arrival times they stand for, in monolayers: band b
    // holds the particles that arrived from b to b + 1 band sizes.
    render::ColourBar band_bar() const {
        const auto& colours = s_.spec.colormap.colours;
        return {render::listed_colormap("bands", {colours.begin() + 1, colours.end()}), 0.0,
                double(s_.bands) * double(band_size_) / double(p_.width), s_.colour_bar_label};
    }

    const Style s_;
    const std::uint64_t band_size_;
    const int monolayers_, view_rows_;
    Description plan_;  // d with one panel at the last monolayer: the run's length
};

std::unique_ptr<Scene> read_deposition(const Description& d, const SceneOptions& options) {
    return std::make_unique<DepositionScene>(d, options);
}

}  // namespace

SceneInfo deposition_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"deposition",
            read_deposition,
            {"band_colormap"},
            {
                {"/panels/*/particles", "particles", "integer", ""},
                {"/panels/*/statistics/mean_height", "mean height", "number", ""},
                {"/panels/*/statistics/roughness", "roughness W", "number", ""},
                {"/panels/*/packing_fraction", "packing fraction", "number", ""},
            }};
}

}  // namespace scenes
