// Ballistic deposition ("Ballistic deposition in Python"): the deposit of
// L^2 particles coloured by arrival time in bands, its growth as a film, and
// the interface's roughness W(L, t) with the fitted KPZ-class exponents.
#include <cmath>

#include "figures/field_spec.hpp"
#include "figures/field_stats.hpp"
#include "figures/plot_page.hpp"
#include "figures/scene.hpp"
#include "figures/step_runner.hpp"
#include "render/colormap.hpp"
#include "render/digest.hpp"
#include "sim/check.hpp"
#include "sim/deposition.hpp"
#include "sim/fractal.hpp"

namespace figures {
namespace {

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
    return render::sha256_hex(flat.data(), flat.size() * sizeof(std::int64_t));
}

// SHA-256 of a roughness curve's times, mean W and its error, in that order.
std::string curve_hash(const sim::RoughnessCurve& curve) {
    std::vector<double> values(curve.times);
    values.insert(values.end(), curve.mean_w.begin(), curve.mean_w.end());
    values.insert(values.end(), curve.sem_w.begin(), curve.sem_w.end());
    return state_hash(values);
}

}  // namespace

void render_deposition(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params("params", d.params,
                    {{"width", "columns L (periodic)"}, {"particles", "particles dropped; the catalog: L^2"}});
    Settings style(
        "style", d.style,
        {{"bands", "arrival-time bands, coloured in turn"}, {"band_colormap", "colormap the bands run through"}});
    sim::DepositionParams p;
    int bands = 0;
    try {
        p.width = params.count("width", 500);
        const long long particles = params.integer("particles", 250000);
        sim::require_integer("particles", particles, 1, 50'000'000);
        p.particles = static_cast<std::uint64_t>(particles);
        p.validate();
        bands = style.count("bands", 20);
        sim::require_integer("bands", bands, 1, 255);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    const render::Colormap& ramp = [&]() -> const render::Colormap& {
        try {
            return render::colormap(style.text("band_colormap", "viridis"));
        } catch (const std::invalid_argument& e) {
            throw UsageError(d.id + ": style.band_colormap: " + e.what());
        }
    }();
    // White for empty cells, then the bands alternating light and dark along the ramp.
    std::vector<glm::vec3> colours = {{1, 1, 1}};
    for (int b = 0; b < bands; ++b) {
        const glm::vec3 c = ramp.at((b + 0.5) / bands);
        colours.push_back(b % 2 ? glm::mix(c, glm::vec3(1), 0.35f) : c);
    }
    const FieldSpec spec{render::listed_colormap("bands", colours), 0.0, double(bands), 1.0f,
                         render::Sampling::nearest};
    const std::uint64_t band_size = (p.particles + bands - 1) / std::uint64_t(bands);

    // Steps of the film are monolayers (L particles); the view is tall enough
    // for the last one: ballistic deposits fill about half their cells.
    const int monolayers = int((p.particles + p.width - 1) / p.width);
    const int view_rows = int(2.4 * monolayers) + 16;
    Description plan = d;
    plan.panels = {monolayers};
    require_drawable(d, "the deposit's view", view_rows, p.width);
    // The deposit's cells (bytes) and the film's field (doubles) over the view.
    require_memory(d, options, {grid_need("cells of a byte and a double", view_rows, p.width, 9, 1)});
    sim::Deposition deposit(p, d.seed);
    // The film's field, kept up to date particle by particle: a drop raises
    // exactly one column, so comparing heights finds where it landed.
    sim::Grid<double> film(view_rows, p.width, 0.0);
    std::vector<std::int64_t> before = deposit.heights();
    auto drop_one = [&] {
        deposit.drop();
        const auto& after = deposit.heights();
        for (int c = 0; c < p.width; ++c)
            if (after[c] != before[c]) {
                if (after[c] <= view_rows)
                    film(view_rows - int(after[c]), c) = double((deposit.dropped() - 1) / band_size + 1);
                before[c] = after[c];
                break;
            }
    };
    StepRunner run(plan, options, progress);
    run.run({.check = {},
             .panel = {},
             .frame =
                 [&](int step) {
                     return draw_field_panels(run.frame_canvas(),
                                              {{format_step(d.animation->title, step), {field_layer(film, spec)}}},
                                              options.scale);
                 },
             .advance =
                 [&] {
                     const std::uint64_t left = p.particles - deposit.dropped();
                     for (std::uint64_t k = 0, n = std::min<std::uint64_t>(left, std::uint64_t(p.width)); k < n; ++k)
                         drop_one();
                     return true;
                 }});

    std::int64_t top = 0;
    for (auto h : deposit.heights()) top = std::max(top, h);
    const int rows = int(top) + 2;
    const auto field = deposit_field(deposit, rows, band_size);
    nlohmann::json meta = {
        {"params", params.used()},
        {"style", style.used()},
        {"panels",
         {{{"particles", deposit.dropped()},
           {"cells", deposit.cells()},
           {"statistics",
            {{"mean_height", deposit.mean_height()}, {"roughness", deposit.roughness()}, {"max_height", top}}},
           {"packing_fraction", double(deposit.cells()) / (double(p.width) * deposit.mean_height())},
           {"band_particles", band_size},
           {"state_sha256", deposit_hash(deposit)}}}},
    };
    run.write_figure(draw_field_panels({{d.panel_title, {field_layer(field, spec)}}}, figure_width(d, options),
                                       figure_height(d, options), options.scale),
                     meta);
}

void render_roughness(const Description& d, const OutputOptions& options, Progress& progress) {
    Settings params(
        "params", d.params,
        {{"widths", "system sizes L"},
         {"seeds", "runs averaged per L"},
         {"saturation_factor", "runs go to t = factor * L^1.5 monolayers (KPZ: saturation at L^z, z = 3/2)"},
         {"points_per_decade", "W samples per decade of t"},
         {"beta_range", "[t1, t2]: growth-regime times fitted for beta, monolayers"},
         {"saturation_from", "W_sat is the mean of W over t >= this fraction of the last time"}});
    Settings style("style", d.style, with_plot_style_keys({{"colours", "one colour per L"}}));
    std::vector<int> widths;
    int seeds = 0, per_decade = 0;
    double factor = 0, from = 0;
    std::vector<double> beta_range;
    try {
        for (long long w : params.integers("widths", {100, 200, 500, 1000, 2000})) {
            sim::require_integer("widths", w, 8, 100000);
            widths.push_back(int(w));
        }
        seeds = params.count("seeds", 4);
        sim::require_integer("seeds", seeds, 1, 1000);
        factor = params.number("saturation_factor", 3.0);
        sim::require_number("saturation_factor", factor, 0.01, 100);
        per_decade = params.count("points_per_decade", 10);
        sim::require_integer("points_per_decade", per_decade, 1, 100);
        beta_range = params.numbers("beta_range", {2, 50});
        if (beta_range.size() != 2 || !(beta_range[1] > beta_range[0]) || beta_range[0] <= 0)
            throw std::invalid_argument("beta_range must be [t1, t2] with 0 < t1 < t2");
        from = params.number("saturation_from", 0.5);
        sim::require_number("saturation_from", from, 0.01, 0.99);
    } catch (const std::invalid_argument& e) {
        throw UsageError(d.id + ": " + e.what());
    }
    if (widths.size() < 2) throw UsageError(d.id + ": params.widths needs at least two sizes to fit alpha");
    const auto colours = style_colours(style, "colours", {"#c6dbef", "#6baed6", "#2171b5", "#08519c", "#08306b"});
    progress.start(d.id, static_cast<long long>(widths.size()));

    render::Axes growth;
    growth.x_scale = growth.y_scale = render::Scale::log;
    growth.x_label = "t (monolayers)";
    growth.y_label = "W(L, t)";
    growth.legend = render::Legend::upper_left;
    std::vector<double> sizes, saturated;
    nlohmann::json curves = nlohmann::json::array();
    std::vector<double> beta_t, beta_w;  // the largest L's growth regime
    for (std::size_t i = 0; i < widths.size(); ++i) {
        const int L = widths[i];
        const double max_time = factor * std::pow(double(L), 1.5);
        const sim::RoughnessCurve curve = sim::roughness_curve(L, max_time, per_decade, seeds, d.seed + i);
        const glm::vec4 colour = colours[i % colours.size()];
        growth.series.push_back(
            line_series(curve.times, curve.mean_w, "L = " + std::to_string(L), colour, 1.8f, false));
        double sum = 0;
        int n = 0;
        for (std::size_t k = 0; k < curve.times.size(); ++k)
            if (curve.times[k] >= from * curve.times.back()) {
                sum += curve.mean_w[k];
                ++n;
            }
        sizes.push_back(L);
        saturated.push_back(sum / n);
        if (i + 1 == widths.size()) {
            for (std::size_t k = 0; k < curve.times.size(); ++k)
                if (curve.times[k] >= beta_range[0] && curve.times[k] <= beta_range[1]) {
                    beta_t.push_back(curve.times[k]);
                    beta_w.push_back(curve.mean_w[k]);
                }
        }
        curves.push_back({{"width", L},
                          {"seeds", seeds},
                          {"max_time", max_time},
                          {"times", curve.times},
                          {"mean_w", curve.mean_w},
                          {"sem_w", curve.sem_w},
                          {"saturated_w", saturated.back()},
                          {"state_sha256", curve_hash(curve)}});
        progress.advance();
    }
    if (beta_t.size() < 2) throw UsageError(d.id + ": params.beta_range holds fewer than two sampled times");
    const sim::LineFit beta = sim::fit_log_log(beta_t, beta_w);
    const sim::LineFit alpha = sim::fit_log_log(sizes, saturated);
    const std::vector<double> beta_line = sim::power_law(beta, beta_t);
    growth.series.push_back(line_series(beta_t, beta_line, "fit, beta = " + format_fixed(beta.slope, 3),
                                        {0.85f, 0.33f, 0.1f, 1}, 2.2f, true));
    growth.notes.push_back({"KPZ: beta = 1/3", {0.62f, 0.10f}, render::Align::left});

    render::Axes scaling;
    scaling.x_scale = scaling.y_scale = render::Scale::log;
    scaling.x_label = "L";
    scaling.y_label = "saturated W";
    scaling.legend = render::Legend::upper_left;
    const std::vector<double> alpha_line = sim::power_law(alpha, sizes);
    scaling.series = {dot_series(sizes, saturated, "W_sat, mean over t >= " + format_fixed(from, 2) + " t_max",
                                 {0.03f, 0.19f, 0.42f, 1}, 8.0f),
                      line_series(sizes, alpha_line, "fit, alpha = " + format_fixed(alpha.slope, 3),
                                  {0.85f, 0.33f, 0.1f, 1}, 2.0f, true)};
    scaling.notes.push_back({"KPZ: alpha = 1/2", {0.62f, 0.10f}, render::Align::left});

    write_figure(d, options,
                 draw_plot_row({growth, scaling}, figure_width(d, options), figure_height(d, options),
                               read_plot_style(style, options.scale)),
                 {{"params", params.used()},
                  {"style", style.used()},
                  {"curves", curves},
                  {"beta", {{"value", beta.slope}, {"fit_range", beta_range}, {"width", widths.back()}, {"r", beta.r}}},
                  {"alpha", {{"value", alpha.slope}, {"widths", sizes}, {"saturated_w", saturated}, {"r", alpha.r}}}});
    progress.finish();
}

}  // namespace figures
