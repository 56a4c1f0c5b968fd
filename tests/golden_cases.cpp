#include "golden_cases.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <filesystem>

#include "description/catalog.hpp"
#include "description/description.hpp"
#include "app/render/render_figure.hpp"
#include "render/gl/canvas.hpp"
#include "render/field.hpp"
#include "render/plot.hpp"
#include "media/png_io.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "render/tubes.hpp"

namespace testkit {

render::Image test_pattern() {
    render::Canvas canvas(160, 96);
    canvas.clear({1, 1, 1, 1});
    // A 6x6 ramp: nearest shows flat cells, smooth a B-spline blur.
    std::vector<double> ramp(36);
    for (int i = 0; i < 36; ++i) ramp[i] = (i % 6 + i / 6) / 10.0;
    render::FieldStyle nearest{&render::colormap("Reds"), 0.0, 1.0, 0.7f, render::Sampling::nearest};
    render::FieldStyle smooth{&render::colormap("viridis"), 0.0, 1.0, 1.0f, render::Sampling::smooth};
    render::draw_field(canvas, {8, 8, 48, 48}, 6, 6, ramp, nearest);
    render::draw_field(canvas, {64, 8, 48, 48}, 6, 6, ramp, smooth);
    render::Shapes shapes;
    shapes.frame({8, 8, 48, 48}, 1, {0, 0, 0, 1});
    shapes.line({120, 10}, {152, 54}, 2.5f, {0, 0, 1, 1});  // diagonal: exercises multisampling
    shapes.rect({120, 60, 30, 8}, {0, 0.5f, 0, 0.5f});
    shapes.draw(canvas);
    static render::Font font(13);
    render::Text text;
    text.add(font, "Ag 10\u207b\u00b3 \u03b1", {8, 84}, {0, 0, 0, 1});
    text.draw(canvas);
    return canvas.read();
}

namespace {

// Two plots side by side: log-log with dashed and solid translucent lines,
// dot markers, a legend and a note; linear with its ticks, reference lines
// and a curve cut at the frame.
render::Image plot_pattern() {
    render::Canvas canvas(520, 260);
    canvas.clear({1, 1, 1, 1});
    render::PlotStyle style;
    style.scale = 0.7f;
    style.wspace = 0.4f;  // room for the second plot's y label
    const std::vector<render::Rect> frames = render::plot_row(520, 260, 2, style);
    const glm::vec4 dark{0.03f, 0.19f, 0.42f, 0.7f}, mid{0.13f, 0.44f, 0.71f, 0.7f}, light{0.42f, 0.68f, 0.84f, 0.7f};
    std::vector<double> n, square, cells, sizes, filled;
    for (int i = 1; i <= 60; ++i) {
        n.push_back(i);
        square.push_back(double(i) * i);
        cells.push_back(std::pow(i, 1.57) * (1 + 0.15 * ((i * 7) % 5 - 2) / 2.0));
    }
    for (int i = 2; i <= 60; i += 5) sizes.push_back(i), filled.push_back(0.6 * std::pow(i, 1.8));
    render::Axes log_log;
    log_log.x_scale = log_log.y_scale = render::Scale::log;
    log_log.x_label = "Time Steps";
    log_log.y_label = "Number of Cells";
    log_log.legend = render::Legend::upper_left;
    log_log.series = {{n, square, "d=2", dark, 3, render::dashed(3), 0},
                      {n, cells, "rule=20", mid, 3, {}, 0},
                      {sizes, filled, "filled", mid, 0, {}, 6},
                      {n, n, "d=1", light, 3, render::dashed(3), 0}};
    log_log.notes = {{"slope 1.57", {0.55f, 0.08f}}};
    render::draw_axes(canvas, frames[0], log_log, style);

    render::Axes linear;
    linear.x_range = std::pair{0.0, 1.0};
    linear.y_range = std::pair{0.0, 1.0};
    linear.x_label = "q";
    linear.y_label = "fraction";
    linear.title = "linear";
    linear.legend = render::Legend::lower_right;
    std::vector<double> q, p;
    for (int i = -10; i <= 110; ++i) q.push_back(i / 100.0), p.push_back(1 / (1 + std::exp(-(i / 100.0 - 0.59) * 25)) * 1.1);
    linear.series = {{q, p, "percolates", {0.84f, 0.15f, 0.16f, 1}, 2, {}, 0}};
    linear.reference_lines = {{render::Direction::horizontal, 0.5, {0.5f, 0.5f, 0.5f, 1}, 1, {4, 2}},
                              {render::Direction::vertical, 0.59, {0, 0, 0, 1}, 1, {}}};
    render::draw_axes(canvas, frames[1], linear, style);
    return canvas.read();
}

// A forked branch in perspective: tapered cones, round joints, depth test,
// lighting, and a 2-D frame drawn after it.
render::Image tubes_pattern() {
    render::Canvas canvas(240, 240, 4, true);
    canvas.clear({1, 1, 1, 1});
    const glm::vec4 bark{0.58f, 0.40f, 0.26f, 1}, leaf{0.42f, 0.76f, 0.30f, 1}, bud{0.85f, 0.30f, 0.35f, 1};
    const std::vector<render::Tube> tubes = {
        {{0, 0, 0}, {0, 2, 0}, 0.30f, 0.22f, bark},
        {{0, 2, 0}, {-1.2f, 3.4f, 0.4f}, 0.22f, 0.14f, bark},
        {{0, 2, 0}, {0.9f, 3.6f, -0.5f}, 0.22f, 0.15f, bark},
        {{-1.2f, 3.4f, 0.4f}, {-1.6f, 4.3f, 1.0f}, 0.14f, 0.08f, leaf},
        {{-1.2f, 3.4f, 0.4f}, {-2.1f, 3.7f, 0.0f}, 0.14f, 0.08f, leaf},
        {{0.9f, 3.6f, -0.5f}, {1.0f, 4.8f, -0.3f}, 0.15f, 0.09f, leaf},
        {{0.9f, 3.6f, -0.5f}, {1.9f, 4.0f, 0.3f}, 0.15f, 0.09f, leaf},
        {{1.0f, 4.8f, -0.3f}, {1.0f, 4.8f, -0.3f}, 0.2f, 0.2f, bud},  // zero length: a ball
    };
    const auto [lo, hi] = render::tube_bounds(tubes);
    const render::Rect viewport{8, 8, 224, 224};
    render::draw_tubes(canvas, viewport, tubes, render::frame_bounds(lo, hi, -25, 20, 1));
    render::Shapes shapes;
    shapes.frame(viewport, 1, {0, 0, 0, 1});
    shapes.draw(canvas);
    return canvas.read();
}

}  // namespace

render::Image render_catalog_figure(const std::string& id, double scale, const std::vector<std::string>& overrides) {
    const description::Description d = description::load_description(description::resolve_figure(id), overrides);
    app::OutputOptions options;
    options.dir = std::filesystem::temp_directory_path() / ("figgen-golden-" + std::to_string(::getpid()));
    options.scale = scale;
    options.video = false;
    scenes::Progress quiet;  // shows nothing
    app::render_figure(d, options, quiet);
    render::Image image = media::read_png(options.dir / (d.id + ".png")).image;
    std::filesystem::remove_all(options.dir);
    return image;
}

std::vector<std::string> golden_overrides(const std::string& id) {
    std::vector<std::string> overrides;
    std::ifstream in(std::filesystem::path(FIGGEN_TEST_GOLDEN_DIR) / (id + ".set"));
    for (std::string line; std::getline(in, line);) {
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        overrides.push_back(line.substr(first, line.find_last_not_of(" \t\r") + 1 - first));
    }
    return overrides;
}

nlohmann::json comparable_metadata(nlohmann::json meta) {
    for (const char* key : {"renderer", "figgen_version", "memory_estimate", "vector"}) meta.erase(key);
    return meta;
}

Rendered render_through_command(const std::string& id, double scale, const std::vector<std::string>& overrides,
                                const std::string& figgen_args) {
    const std::filesystem::path out =
        std::filesystem::temp_directory_path() / ("figgen-golden-" + id + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(out);
    std::ostringstream command;
    const bool formats = figgen_args.find("--format") != std::string::npos;
    command << FIGGEN_EXE << " render " << id << (formats ? "" : " --no-video") << " --scale " << scale << " --out '"
            << out.string() << "' " << figgen_args;
    for (const std::string& o : overrides) command << " --set '" << o << "'";
    command << " 2>&1";
    std::string output;
    std::FILE* pipe = ::popen(command.str().c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command.str());
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    const int status = ::pclose(pipe);
    if (status != 0) {
        std::filesystem::remove_all(out);
        throw std::runtime_error(command.str() + " failed (status " + std::to_string(status) + "): " + output);
    }
    Rendered r;
    r.image = media::read_png(out / (id + ".png")).image;
    std::ifstream in(out / (id + ".json"));
    r.meta = nlohmann::json::parse(in);
    for (const char* extension : {".pdf", ".svg"})
        if (std::filesystem::exists(out / (id + extension))) {
            if (r.vector_dir.empty()) {
                r.vector_dir = out.string() + "-vector";
                std::filesystem::remove_all(r.vector_dir);
                std::filesystem::create_directory(r.vector_dir);
            }
            std::filesystem::rename(out / (id + extension), r.vector_dir / (id + extension));
        }
    std::filesystem::remove_all(out);
    return r;
}

std::vector<GoldenCase> golden_cases() {
    const auto pattern = [](render::Image (*draw)()) {
        return [draw](const std::string&) { return Rendered{draw(), nullptr, {}}; };
    };
    std::vector<GoldenCase> cases = {{"test-pattern", pattern(test_pattern)},
                                     {"plot-pattern", pattern(plot_pattern)},
                                     {"tubes-pattern", pattern(tubes_pattern)}};
    for (const auto& file : description::catalog_files()) {
        const std::string id = file.stem().string();
        cases.push_back({id,
                         [id](const std::string& args) {
                             return render_through_command(id, golden_scale, golden_overrides(id), args);
                         },
                         true});
    }
    return cases;
}

}  // namespace testkit
