#include "golden_cases.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "figures/catalog.hpp"
#include "figures/description.hpp"
#include "figures/scene.hpp"
#include "render/canvas.hpp"
#include "render/field.hpp"
#include "render/png_io.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"

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

render::Image render_catalog_figure(const std::string& id, double scale) {
    const figures::Description d = figures::load_description(figures::resolve_figure(id));
    figures::OutputOptions options;
    options.dir = std::filesystem::temp_directory_path() / ("figgen-golden-" + std::to_string(::getpid()));
    options.scale = scale;
    options.video = false;
    figures::Progress quiet(false);
    figures::render_figure(d, options, quiet);
    render::Image image = render::read_png(options.dir / (d.id + ".png")).image;
    std::filesystem::remove_all(options.dir);
    return image;
}

std::vector<GoldenCase> golden_cases() {
    std::vector<GoldenCase> cases = {{"test-pattern", test_pattern}};
    for (const auto& file : figures::catalog_files()) {
        const std::string id = file.stem().string();
        cases.push_back({id, [id] { return render_catalog_figure(id, golden_scale); }});
    }
    return cases;
}

}  // namespace testkit
