// The snowflakes' fractal dimension (Liu & Zhang 1987, section 4): the ice
// mass M(l) within distance l of the seed against l, log-log, each rule's
// slope D fitted over a stated range. These are finite-size estimates: the
// paper claims 1 < D < 2, while Gravner & Griffeath (2006) prove that rules
// freezing on exactly one neighbour fill the plane with positive density, so
// their slopes tend to 2 as crystals grow.
#include <cmath>

#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "figures/snowflake_setup.hpp"
#include "render/colormap.hpp"
#include "sim/check.hpp"
#include "sim/fractal.hpp"

namespace figures {

void render_snowflake_dimension(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    snowflake_keys({{"fit_from", "smallest distance l fitted, cells"},
                                    {"fit_to", "largest distance fitted, as a fraction of the crystal's radius"}}));
    Settings style("style", d.style, with_plot_style_keys({{"colours", "one colour per run"}}));
    const std::vector<SnowflakeRun> runs = read_snowflake_runs(params, d.id);
    int steps = 0, fit_from = 0;
    double fit_to = 0;
    try {
        steps = params.count("steps", 200);
        sim::require_integer("steps", steps, 8, 100000);
        fit_from = params.count("fit_from", 4);
        sim::require_integer("fit_from", fit_from, 1, steps);
        fit_to = params.number("fit_to", 0.5);
        sim::require_number("fit_to", fit_to, 0.05, 1.0);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const auto colours =
        style_colours(style, "colours", {"#08306b", "#2171b5", "#6baed6", "#e6550d", "#31a354", "#756bb1", "#636363"});
    progress.start(d.id, static_cast<long long>(runs.size()));

    render::Axes axes;
    axes.x_scale = axes.y_scale = render::Scale::log;
    axes.x_label = "Distance from the seed l (cells)";
    axes.y_label = "Ice cells M(l)";
    axes.legend = render::Legend::upper_left;
    nlohmann::json fits = nlohmann::json::array();
    std::vector<double> all_l;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        sim::Snowflake crystal(runs[i].params);
        for (int s = 0; s < steps; ++s) crystal.step();
        const int max_l = static_cast<int>(std::floor(crystal.euclidean_radius()));
        const std::vector<long> mass = sim::mass_within(crystal, max_l);
        std::vector<double> l, m, fit_l, fit_m;
        const int fit_last = static_cast<int>(std::floor(fit_to * crystal.euclidean_radius()));
        for (int k = 1; k <= max_l; ++k) {
            l.push_back(k);
            m.push_back(double(mass[k - 1]));
            if (k >= fit_from && k <= fit_last) {
                fit_l.push_back(k);
                fit_m.push_back(double(mass[k - 1]));
            }
        }
        if (fit_l.size() < 2)
            throw UsageError(d.id + ": the fit range " + std::to_string(fit_from) + ".." + std::to_string(fit_last) +
                             " holds fewer than two distances; raise steps or fit_to");
        const sim::LineFit fit = sim::fit_log_log(fit_l, fit_m);
        const glm::vec4 colour = colours[i % colours.size()];
        std::string rule = runs[i].params.rule.code();
        const auto& restriction = runs[i].params.restriction;
        if (restriction.last >= restriction.first)
            rule += " restricted " + std::to_string(restriction.first) + "\u2013" + std::to_string(restriction.last);
        if (!runs[i].params.priority.steps.empty()) rule += " with priority";
        axes.series.push_back(line_series(l, m, rule + ", D = " + format_fixed(fit.slope, 2), colour, 2.0f, false));
        // The fitted line over its range, dashed.
        const std::vector<double> line_m = sim::power_law(fit, fit_l);
        axes.series.push_back(line_series(fit_l, line_m, "", colour, 1.2f, true));
        nlohmann::json meta = snowflake_settings(runs[i].params);
        meta.update({{"steps", steps},
                     {"ice", crystal.ice_count()},
                     {"euclidean_radius", crystal.euclidean_radius()},
                     {"fit_range", {fit_from, fit_last}},
                     {"dimension", fit.slope},
                     {"r", fit.r},
                     {"state_sha256", state_hash(m)}});
        fits.push_back(meta);
        progress.advance();
    }
    // A filled plane: 2 / sqrt(3) cells per unit area, so M(l) = (2 pi / sqrt 3) l^2.
    const double filled = 2 * M_PI / std::sqrt(3.0);
    const std::vector<double> ref_l = {1.0, double(steps)};
    axes.series.push_back(
        line_series(ref_l, {filled, filled * steps * steps}, "filled plane, D = 2", {0.6f, 0.6f, 0.6f, 1}, 1.0f, true));
    write_figure(d, options,
                 draw_plot_row({axes}, figure_width(d, options), figure_height(d, options),
                               read_plot_style(style, options.scale)),
                 {{"params", params.used()}, {"style", style.used()}, {"fits", fits}});
    progress.finish();
}

}  // namespace figures
