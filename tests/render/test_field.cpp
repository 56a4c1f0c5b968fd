#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "render/gl/canvas.hpp"
#include "render/colormap.hpp"
#include "render/field.hpp"

namespace {

// Two smooth 60 x 50 layers over most of their range, like Gray-Scott's A and B.
struct Layers {
    std::vector<double> a, b;
    Layers() {
        for (int i = 0; i < 60 * 50; ++i) {
            const int r = i / 60, c = i % 60;
            a.push_back(0.5 + 0.5 * std::sin(0.21 * r) * std::cos(0.13 * c));
            b.push_back(0.5 + 0.45 * std::cos(0.17 * r + 0.3) * std::sin(0.11 * c));
        }
    }
};

render::Image draw(const Layers& l, bool paired, render::Sampling sampling) {
    render::Canvas canvas(240, 200, 1);
    canvas.clear({1, 1, 1, 1});
    const render::FieldStyle reds{&render::colormap("Reds"), 0.0, 1.0, 0.7f, sampling},
        blues{&render::colormap("Blues"), 0.0, 1.0, 0.7f, sampling};
    const render::Rect where{10, 10, 220, 180};
    if (paired) {
        render::draw_field_pair(canvas, where, 50, 60, l.a, reds, l.b, blues);
    } else {
        render::draw_field(canvas, where, 50, 60, l.a, reds);
        render::draw_field(canvas, where, 50, 60, l.b, blues);
    }
    return canvas.read();
}

}  // namespace

TEST_CASE("two layers drawn in one pass match two draws but for rounding", "[field]") {
    const Layers layers;
    for (const auto sampling : {render::Sampling::nearest, render::Sampling::smooth}) {
        const render::Image separate = draw(layers, false, sampling), paired = draw(layers, true, sampling);
        REQUIRE(separate.rgba.size() == paired.rgba.size());
        int largest = 0;
        std::size_t differing = 0;
        for (std::size_t i = 0; i < separate.rgba.size(); ++i) {
            const int d = std::abs(int(separate.rgba[i]) - int(paired.rgba[i]));
            largest = std::max(largest, d);
            differing += d != 0;
        }
        // Two blends round to 8 bits twice (llvmpipe blends in 8-bit fixed
        // point), one pass once: measured here, at most 2 levels.
        CHECK(largest <= 2);
        CHECK(differing < separate.rgba.size() / 2);
        // Not trivially equal: the field is drawn, reds and blues mixed.
        const std::uint8_t* centre = paired.pixel(120, 100);
        CHECK(centre[0] < 250);
        CHECK(centre[2] < 250);
        CHECK(paired.pixel(2, 2)[0] == 255);  // the white margin
    }
}

TEST_CASE("a smooth pair resampled by the GPU's sampler matches the CPU's spline but for rounding", "[field]") {
    // What a GPU draws a film's frame with (FieldResampling::sampler) against
    // llvmpipe's CPU spline: the same cubic B-spline, the sampler's
    // bilinear weights rounded to its 8 fractional bits.
    const Layers layers;
    render::set_field_resampling(render::FieldResampling::cpu);
    const render::Image cpu = draw(layers, true, render::Sampling::smooth);
    render::set_field_resampling(render::FieldResampling::sampler);
    const render::Image sampler = draw(layers, true, render::Sampling::smooth);
    render::set_field_resampling(render::FieldResampling::automatic);
    CHECK(draw(layers, true, render::Sampling::smooth).rgba == cpu.rgba);  // llvmpipe here: the CPU's
    REQUIRE(cpu.rgba.size() == sampler.rgba.size());
    int largest = 0;
    double total = 0;
    for (std::size_t i = 0; i < cpu.rgba.size(); ++i) {
        const int d = std::abs(int(cpu.rgba[i]) - int(sampler.rgba[i]));
        largest = std::max(largest, d);
        total += d;
    }
    INFO("largest difference " << largest << ", mean " << total / double(cpu.rgba.size()));
    CHECK(largest <= 4);
    CHECK(total / double(cpu.rgba.size()) < 0.5);
    CHECK(cpu.rgba != sampler.rgba);  // two paths really taken
}

TEST_CASE("a pair of layers that do not fit one grid or sampling is refused", "[field]") {
    render::Canvas canvas(20, 20, 1);
    const std::vector<double> four(4, 0.5), six(6, 0.5);
    const render::FieldStyle nearest{&render::colormap("Reds"), 0.0, 1.0, 0.7f, render::Sampling::nearest},
        smooth{&render::colormap("Blues"), 0.0, 1.0, 0.7f, render::Sampling::smooth};
    CHECK_THROWS_WITH(render::draw_field_pair(canvas, {0, 0, 20, 20}, 2, 2, four, nearest, six, nearest),
                      Catch::Contains("6 values do not fill 2x2 cells"));
    CHECK_THROWS_WITH(render::draw_field_pair(canvas, {0, 0, 20, 20}, 2, 2, four, nearest, four, smooth),
                      Catch::Contains("sampling"));
}
