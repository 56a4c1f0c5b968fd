// `make bench`, second half: run time against error, x264's settings on
// figgen's frames, the book's route side by side, and whole-pipeline times. Results go to bench/results/latest.json;
// the Pareto figure (run time against error, log-log, one curve per method)
// to out/bench-pareto.png, drawn with figgen's own plot layer.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "accuracy.hpp"
#include "scenes/helpers/plot_page.hpp"
#include "base/atomic_file.hpp"
#include "render/gl/canvas.hpp"
#include "render/colormap.hpp"
#include "media/png_io.hpp"

namespace {

render::Series series_of(const bench::Curve& curve) {
    std::vector<double> x, y;
    for (const auto& p : curve.points) {
        x.push_back(p.seconds);
        y.push_back(p.error);
    }
    auto s = scenes::line_series(x, y, curve.label, glm::vec4(render::parse_colour(curve.colour), 1), 1.8f, false);
    s.marker_size = 7;
    return s;
}

render::Axes pareto_axes(const std::vector<bench::Curve>& curves, const std::string& title,
                         std::pair<double, double> errors, render::Legend legend) {
    render::Axes axes;
    axes.y_range = errors;  // room for the legend clear of the curves
    axes.x_scale = axes.y_scale = render::Scale::log;
    axes.x_label = "run time (s)";
    axes.y_label = "error";
    axes.title = title;
    axes.legend = legend;
    for (const auto& c : curves) axes.series.push_back(series_of(c));
    return axes;
}

// Two plots side by side, 1600 x 700, into a PNG titled `title`.
void write_plot_pair(const std::filesystem::path& file, render::Axes left, render::Axes right, const char* title) {
    render::PlotStyle style;
    style.wspace = 0.3f;
    render::Canvas canvas(1600, 700, render::canvas_samples);
    canvas.background({1, 1, 1, 1});
    scenes::draw_plot_row(canvas, {0, 0, 1600, 700}, {std::move(left), std::move(right)}, style);
    media::write_png(file, canvas.read(), {{"Title", title}});
}

void write_pareto(const std::filesystem::path& file, const bench::Curves& curves) {
    write_plot_pair(file,
                    pareto_axes(curves.numerics, "Arithmetic against exact solutions", {1e-17, 1.0},
                                render::Legend::upper_left),
                    pareto_axes(curves.estimators, "Estimates against known constants", {1e-6, 1.0},
                                render::Legend::lower_left),
                    "figgen: run time against error");
}

// A formula model's integrators: the same axes, one curve per integrator.
void write_integrators(const std::filesystem::path& file, const bench::Curves& curves) {
    write_plot_pair(file,
                    pareto_axes(curves.integrators_known, "Heat equation's Fourier mode against its exact decay",
                                {1e-16, 1.0}, render::Legend::upper_right),
                    pareto_axes(curves.integrators_reference, "Gray-Scott against RK4 at a timestep of 1/128",
                                {1e-10, 1.0}, render::Legend::upper_right),
                    "figgen: a formula model's integrators, run time against error");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app("figgen_accuracy: run time against error, the book's route, whole-pipeline times");
    bench::Paths paths{FIGGEN_SOURCE_DIR, FIGGEN_BINARY_DIR, FIGGEN_EXE, "bench/results"};
    std::filesystem::path figure_dir = "out";
    long long long_run = 1'000'000;
    bool skip_pipeline = false, skip_encoder = false, encoder_only = false, integrators_only = false;
    app.add_option("--results", paths.results, "folder for latest.json and the book's route's peer.json");
    app.add_option("--figures", figure_dir, "folder for bench-pareto.png");
    app.add_option("--long-run", long_run, "steps of the Gray-Scott stability run at n = 64")->check(CLI::Range(0LL, 100'000'000LL));
    app.add_flag("--no-pipeline", skip_pipeline, "skip the book's route and the whole-pipeline times");
    app.add_flag("--no-encoder", skip_encoder, "skip the x264 presets and tunes (bench/results/encoder.md)");
    app.add_flag("--encoder-only", encoder_only, "only the x264 presets and tunes: encoder.json and encoder.md");
    app.add_flag("--integrators-only", integrators_only,
                 "only a formula model's integrators: integrators.json and bench-integrators.png");
    CLI11_PARSE(app, argc, argv);
    try {
        std::filesystem::create_directories(paths.results);
        if (encoder_only) {
            bench::encoder_settings(paths);
            std::printf("wrote %s\n", (paths.results / "encoder.md").c_str());
            return 0;
        }
        bench::Curves curves;
        if (integrators_only) {
            const nlohmann::json integrators = bench::formula_integrators(curves);
            std::filesystem::create_directories(figure_dir);
            base::write_file_atomically(paths.results / "integrators.json", integrators.dump(2) + "\n");
            write_integrators(figure_dir / "bench-integrators.png", curves);
            std::printf("wrote %s and %s\n", (paths.results / "integrators.json").c_str(),
                        (figure_dir / "bench-integrators.png").c_str());
            return 0;
        }
        nlohmann::json out;
        std::fprintf(stderr, "figgen_accuracy: arithmetic and estimators\n");
        out["gray_scott_float_vs_double"] = bench::gray_scott_float_vs_double(curves);
        out["diffusion_vs_exact"] = bench::diffusion_vs_exact(curves);
        out["percolation_threshold"] = bench::percolation_threshold(curves);
        out["fractal_dimensions"] = bench::fractal_dimensions(curves);
        std::fprintf(stderr, "figgen_accuracy: Gray-Scott stability, %lld steps at n = 64\n", long_run);
        out["gray_scott_long_run"] = bench::gray_scott_long_run(long_run);
        std::fprintf(stderr, "figgen_accuracy: a formula model's integrators\n");
        out["formula_integrators"] = bench::formula_integrators(curves);
        if (!skip_encoder) out["encoder"] = bench::encoder_settings(paths);
        if (!skip_pipeline) {
            out["book_route"] = bench::peer_comparison(paths);
            std::fprintf(stderr, "figgen_accuracy: whole-pipeline times (make figures from clean)\n");
            out["pipeline"] = bench::pipeline_times(paths, out["book_route"]);
            std::fprintf(stderr, "figgen_accuracy: film segment lengths (bytes against parallelism)\n");
            out["segment_lengths"] = bench::segment_lengths(paths);
        }
        out["targets"] = bench::target_table(out, paths);
        // After the pipeline study, which starts out/ afresh.
        std::filesystem::create_directories(figure_dir);
        base::write_file_atomically(paths.results / "latest.json", out.dump(2) + "\n");
        write_pareto(figure_dir / "bench-pareto.png", curves);
        write_integrators(figure_dir / "bench-integrators.png", curves);
        std::printf("wrote %s, %s and %s\n", (paths.results / "latest.json").c_str(),
                    (figure_dir / "bench-pareto.png").c_str(), (figure_dir / "bench-integrators.png").c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "figgen_accuracy: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
