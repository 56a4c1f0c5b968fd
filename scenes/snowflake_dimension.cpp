// The snowflakes' fractal dimension (Liu & Zhang 1987, section 4): the ice
// mass M(l) within distance l of the seed against l, log-log, each rule's
// slope D fitted over a stated range. These are finite-size estimates: the
// paper claims 1 < D < 2, while Gravner & Griffeath (2006) prove that rules
// freezing on exactly one neighbour fill the plane with positive density, so
// their slopes tend to 2 as crystals grow.
#include <cmath>
#include <stdexcept>

#include "render/colormap.hpp"
#include "scenes/helpers/field_stats.hpp"
#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "scenes/helpers/snowflake_setup.hpp"
#include "scenes/scene.hpp"
#include "sim/fractal.hpp"

namespace scenes {
namespace {

struct Params {
    SnowflakeSetup setup;
    int steps = 200, fit_from = 4;
    double fit_to = 0.5;
};

const Schema<Params> param_schema =
    Schema<Params>()
        .part(snowflake_schema(), &Params::setup)
        .count("steps", &Params::steps, "steps of every run", 8, snowflake_most_steps)
        .key({"fit_from", "smallest distance l fitted, cells", "an integer", "an integer from 1 to steps", 4},
             [](Settings& s, const std::string& key, Params& p) {
                 p.fit_from = s.count_in(key, p.fit_from, 1, p.steps);
             })
        .number("fit_to", &Params::fit_to, "largest distance fitted, as a fraction of the crystal's radius", 0.05, 1.0);

struct Style {
    std::vector<Colour> colours{colour("#08306b"), colour("#2171b5"), colour("#6baed6"), colour("#e6550d"),
                                colour("#31a354"), colour("#756bb1"), colour("#636363")};
    PlotSettings plot;
};

const Schema<Style> style_schema =
    Schema<Style>()
        .field({"colours", "one colour per run", "a list of colours"}, &Style::colours, read_colours)
        .part(plot_settings_schema(), &Style::plot);

// A list of steps as messages show it: "[16, 200]".

// A run's legend: its rule, and its restriction and priority if any.
std::string legend_of(const sim::SnowflakeParams& p) {
    std::string rule = p.rule.code();
    const auto& restriction = p.restriction;
    if (restriction.last >= restriction.first)
        rule += " restricted " + std::to_string(restriction.first) + "\u2013" + std::to_string(restriction.last);
    if (!p.priority.steps.empty()) rule += " with priority";
    return rule;
}

class SnowflakeDimensionScene : public SceneBase {
public:
    SnowflakeDimensionScene(const Description& d, const SceneOptions& options)
        : SceneBase(d, options, param_schema.keys(), style_schema.keys()),
          p_(param_schema.read(params_)),
          s_(style_schema.read(style_)),
          plot_style_(plot_style(s_.plot, options.scale)) {
        refuse_empty_fit();
        refuse_steps(d, "the plot shows every crystal at params.steps", true);
    }

    // One crystal at a time, grown to params.steps, and its masses.
    std::vector<MemoryNeed> memory() const override {
        double bytes = 0;
        for (const auto& run : p_.setup.runs)
            bytes = std::max(bytes, snowflake_crystal_bytes(snowflake_radius_bound(run.params, p_.steps)) +
                                        sizeof(long) * (p_.steps + 1.0));
        return {{"a crystal of " + std::to_string(p_.steps) + " steps", bytes}};
    }

    void render(Output& out) const override {
        Progress& progress = out.progress();
        progress.start(d_.id, static_cast<long long>(p_.setup.runs.size()));
        render::Axes axes;
        axes.x_scale = axes.y_scale = render::Scale::log;
        axes.x_label = "Distance from the seed l (cells)";
        axes.y_label = "Ice cells M(l)";
        axes.legend = render::Legend::upper_left;
        nlohmann::json fits = nlohmann::json::array();
        for (std::size_t i = 0; i < p_.setup.runs.size(); ++i) {
            fits.push_back(fit_run(i, axes));
            progress.advance();
        }
        // A filled plane: 2 / sqrt(3) cells per unit area, so M(l) = (2 pi / sqrt 3) l^2.
        const double filled = 2 * M_PI / std::sqrt(3.0);
        const std::vector<double> ref_l = {1.0, double(p_.steps)};
        axes.series.push_back(line_series(ref_l, {filled, filled * p_.steps * p_.steps}, "filled plane, D = 2",
                                          {0.6f, 0.6f, 0.6f, 1}, 1.0f, true));
        out.figure(plot_figure({axes}, d_, options_, plot_style_),
                   {{"params", params_.used()}, {"style", style_.used()}, {"fits", fits}});
        progress.finish();
    }

private:
    // A crystal grows at most a ring a step, and a cell's distance from the
    // seed is at most its ring: fit_to x steps bounds the fit's last
    // distance, and the range must hold two distances even then.
    void refuse_empty_fit() {
        if (p_.fit_from + 1 > p_.steps)
            params_.refuse("fit_from",
                           "an integer from 1 to steps - 1 = " + std::to_string(p_.steps - 1) +
                               ": the fit needs two distances, and a crystal's radius grows at most a cell a step");
        if (static_cast<int>(std::floor(p_.fit_to * double(p_.steps))) < p_.fit_from + 1)
            params_.refuse(
                "fit_to",
                "a number from (fit_from + 1) / steps = " + description::shown(double(p_.fit_from + 1) / p_.steps) +
                    " to 1: the fit needs two distances, and a crystal's radius grows at most a cell a step");
    }

    // Run i grown `steps`: its M(l), its fit (dashed) on `axes`, and its metadata.
    nlohmann::json fit_run(std::size_t i, render::Axes& axes) const {
        sim::Snowflake crystal(p_.setup.runs[i].params);
        for (int s = 0; s < p_.steps; ++s) crystal.step();
        const int max_l = static_cast<int>(std::floor(crystal.euclidean_radius()));
        const std::vector<long> mass = sim::mass_within(crystal, max_l);
        std::vector<double> l, m, fit_l, fit_m;
        const int fit_last = static_cast<int>(std::floor(p_.fit_to * crystal.euclidean_radius()));
        for (int k = 1; k <= max_l; ++k) {
            l.push_back(k);
            m.push_back(double(mass[k - 1]));
            if (k >= p_.fit_from && k <= fit_last) {
                fit_l.push_back(k);
                fit_m.push_back(double(mass[k - 1]));
            }
        }
        // Phase 1 refuses a range too short for any crystal; this one grew too
        // slowly for it, which only the run can tell: a failure of the run.
        if (fit_l.size() < 2)
            throw std::runtime_error(d_.id + ": " + p_.setup.runs[i].label + "'s crystal reached radius " +
                                     format_fixed(crystal.euclidean_radius(), 2) + ", too small for a fit from " +
                                     std::to_string(p_.fit_from) + " to " + std::to_string(fit_last) +
                                     " (two distances at least); raise steps or fit_to; no image written");
        const sim::LineFit fit = sim::fit_log_log(fit_l, fit_m);
        const glm::vec4 colour = s_.colours[i % s_.colours.size()].rgba;
        axes.series.push_back(line_series(
            l, m, legend_of(p_.setup.runs[i].params) + ", D = " + format_fixed(fit.slope, 2), colour, 2.0f, false));
        // The fitted line over its range, dashed.
        const std::vector<double> line_m = sim::power_law(fit, fit_l);
        axes.series.push_back(line_series(fit_l, line_m, "", colour, 1.2f, true));
        nlohmann::json meta = snowflake_settings(p_.setup.runs[i].params);
        meta.update({{"steps", p_.steps},
                     {"ice", crystal.ice_count()},
                     {"euclidean_radius", crystal.euclidean_radius()},
                     {"fit_range", {p_.fit_from, fit_last}},
                     {"dimension", fit.slope},
                     {"r", fit.r},
                     {"state_sha256", state_hash(m)}});
        return meta;
    }

    const Params p_;
    const Style s_;
    const render::PlotStyle plot_style_;
};

std::unique_ptr<Scene> read_snowflake_dimension(const Description& d, const SceneOptions& options) {
    return std::make_unique<SnowflakeDimensionScene>(d, options);
}

}  // namespace

SceneInfo snowflake_dimension_scene() {
    // Its key numbers (app/gallery/key_numbers.hpp), with the catalog's reference values (docs/catalog.md).
    return {"snowflake_dimension",
            read_snowflake_dimension,
            {},
            {
                {"/fits/*/dimension",
                 "D, {rule}{restriction| restricted}",
                 "number",
                 "",
                 {{"", "1 < D < 2 (paper); tends to 2 (Gravner & Griffeath 2006)"}}},
                {"/fits/*/fit_range", "fit range l, {rule}{restriction| restricted}", "range", "cells"},
            }};
}

}  // namespace scenes
