#include <catch2/catch.hpp>

#include "render/gl/canvas.hpp"
#include "render/colormap.hpp"
#include "render/field.hpp"

// Reference colours: the end points of ColorBrewer's 9-class sequential
// schemes (Reds #fff5f0 .. #67000d, Blues #f7fbff .. #08306b, Greens
// #f7fcf5 .. #00441b) that matplotlib interpolates, and viridis's published
// first and last entries (0.267004, 0.004874, 0.329415), (0.993248, 0.906157, 0.143936).

namespace {
void check_rgb(glm::vec3 actual, int r, int g, int b) {
    CHECK(actual.r * 255 == Approx(r).margin(0.01));
    CHECK(actual.g * 255 == Approx(g).margin(0.01));
    CHECK(actual.b * 255 == Approx(b).margin(0.01));
}
}  // namespace

TEST_CASE("colormaps hold matplotlib's tables", "[colormap]") {
    check_rgb(render::colormap("Reds").at(0.0), 0xff, 0xf5, 0xf0);
    check_rgb(render::colormap("Reds").at(1.0), 0x67, 0x00, 0x0d);
    check_rgb(render::colormap("Blues").at(0.0), 0xf7, 0xfb, 0xff);
    check_rgb(render::colormap("Blues").at(1.0), 0x08, 0x30, 0x6b);
    check_rgb(render::colormap("Greens").at(0.0), 0xf7, 0xfc, 0xf5);
    check_rgb(render::colormap("Greens").at(1.0), 0x00, 0x44, 0x1b);
    const glm::vec3 v0 = render::colormap("viridis").at(0.0), v1 = render::colormap("viridis").at(1.0);
    CHECK(v0.r == Approx(0.267004).margin(1e-6));
    CHECK(v0.b == Approx(0.329415).margin(1e-6));
    CHECK(v1.r == Approx(0.993248).margin(1e-6));
    CHECK(v1.b == Approx(0.143936).margin(1e-6));
}

TEST_CASE("colormap lookup quantises like matplotlib and clips out-of-range values", "[colormap]") {
    const auto& reds = render::colormap("Reds");
    CHECK(reds.at(-3.0) == reds.at(0.0));
    CHECK(reds.at(7.0) == reds.at(1.0));
    CHECK(reds.at(0.5) == reds.colours[128]);
    CHECK(reds.at(0.5 - 1e-9) == reds.colours[127]);
}

TEST_CASE("a listed colormap gives integer states their own colours as matplotlib does", "[colormap]") {
    // ListedColormap(['white', 'green', 'orange']) with vmin 0, vmax 2.
    const auto forest = render::listed_colormap("forest", {render::parse_colour("white"), render::parse_colour("green"),
                                                           render::parse_colour("#ffa500")});
    CHECK(forest.at(0.0 / 2) == glm::vec3(1, 1, 1));
    CHECK(forest.at(1.0 / 2) == glm::vec3(0, 128 / 255.0f, 0));
    CHECK(forest.at(2.0 / 2) == glm::vec3(1, 165 / 255.0f, 0));
    CHECK(forest.at(0.33) == glm::vec3(1, 1, 1));  // floor(0.33 * 3) = 0
    CHECK(forest.at(0.34) == glm::vec3(0, 128 / 255.0f, 0));
    CHECK_THROWS_WITH(render::parse_colour("#12345"), Catch::Contains("use #rrggbb or one of white"));
}

TEST_CASE("an unknown colormap is an error listing the known ones", "[colormap]") {
    CHECK_THROWS_WITH(render::colormap("jet"), "colormap \"jet\" is unknown: allowed are Reds, Blues, Greens, viridis, "
                                                "inferno, magma, plasma, cividis");
}

TEST_CASE("inferno, magma, plasma and cividis end where matplotlib's listed data do", "[colormap]") {
    // The first and last rows of matplotlib's _cm_listed.py tables.
    const struct {
        const char* name;
        glm::vec3 first, last;
    } maps[] = {
        {"inferno", {0.001462f, 0.000466f, 0.013866f}, {0.988362f, 0.998364f, 0.644924f}},
        {"magma", {0.001462f, 0.000466f, 0.013866f}, {0.987053f, 0.991438f, 0.749504f}},
        {"plasma", {0.050383f, 0.029803f, 0.527975f}, {0.940015f, 0.975158f, 0.131326f}},
        {"cividis", {0.0f, 0.135112f, 0.304751f}, {0.995737f, 0.909344f, 0.217772f}},
    };
    for (const auto& m : maps) {
        INFO(m.name);
        const auto& map = render::colormap(m.name);
        REQUIRE(map.colours.size() == 256);
        for (int c = 0; c < 3; ++c) {
            CHECK(map.at(0.0)[c] == Approx(m.first[c]).margin(1e-6));
            CHECK(map.at(1.0)[c] == Approx(m.last[c]).margin(1e-6));
        }
    }
}

TEST_CASE("a nearest-sampled field paints each cell its colour, alpha-blended over white", "[colormap][field]") {
    render::Canvas canvas(40, 40);
    canvas.clear({1, 1, 1, 1});
    const std::vector<double> values = {0.0, 1.0, 0.5, 0.25};  // 2x2, row 0 at the top
    const auto& reds = render::colormap("Reds");
    render::draw_field(canvas, {0, 0, 40, 40}, 2, 2, values, {&reds, 0.0, 1.0, 0.7f, render::Sampling::nearest});
    const render::Image image = canvas.read();
    auto expect_cell = [&](int x, int y, double value) {
        const glm::vec3 c = reds.at(value);
        for (int ch = 0; ch < 3; ++ch) {
            const double over_white = 0.7 * c[ch] + 0.3;  // straight alpha over an opaque white page
            CHECK(int(image.pixel(x, y)[ch]) == Approx(over_white * 255).margin(1.5));  // 8-bit blending rounds twice
        }
        CHECK(int(image.pixel(x, y)[3]) == 255);
    };
    expect_cell(10, 10, 0.0);   // top-left cell
    expect_cell(30, 10, 1.0);   // top-right
    expect_cell(10, 30, 0.5);   // bottom-left
    expect_cell(30, 30, 0.25);  // bottom-right
}

TEST_CASE("smooth sampling keeps a constant field constant and blends across an edge", "[field]") {
    render::Canvas canvas(64, 16);
    canvas.clear({1, 1, 1, 1});
    const auto& viridis = render::colormap("viridis");
    // 1 x 8 cells: 0 0 0 0 1 1 1 1.
    const std::vector<double> step = {0, 0, 0, 0, 1, 1, 1, 1};
    render::draw_field(canvas, {0, 0, 64, 16}, 1, 8, step, {&viridis, 0.0, 1.0, 1.0f, render::Sampling::smooth});
    const render::Image image = canvas.read();
    const glm::vec3 low = viridis.at(0.0), high = viridis.at(1.0);
    CHECK(int(image.pixel(2, 8)[0]) == Approx(low.r * 255).margin(1.0));   // far from the edge: flat
    CHECK(int(image.pixel(61, 8)[0]) == Approx(high.r * 255).margin(1.0));
    // At the edge (x = 32) the B-spline gives 0.5: viridis's middle colour.
    const glm::vec3 mid = viridis.at(0.5);
    CHECK(int(image.pixel(32, 8)[0]) == Approx(mid.r * 255).margin(12.0));
    CHECK(int(image.pixel(32, 8)[1]) == Approx(mid.g * 255).margin(12.0));
}
