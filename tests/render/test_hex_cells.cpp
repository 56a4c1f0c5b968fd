#include <catch2/catch.hpp>

#include <cmath>

#include "render/gl/canvas.hpp"
#include "render/hex_cells.hpp"

namespace {
bool inked(const render::Image& image, glm::vec2 at) {
    return image.pixel(int(at.x), int(at.y))[1] < 128;  // drawn in black on white
}
}  // namespace

TEST_CASE("hexagons tile the lattice with the area of a regular hexagon", "[hex]") {
    render::Canvas canvas(200, 200);
    canvas.clear({1, 1, 1, 1});
    const render::HexView view{{100, 100}, 20};
    const std::vector<glm::ivec2> flower = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}};
    render::draw_hex_cells(canvas, view, flower, {0, 0, 0, 1});
    const render::Image image = canvas.read();
    long ink = 0;
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) ink += inked(image, {x + 0.5f, y + 0.5f});
    // Seven regular hexagons of circumradius 20: 7 * (3 sqrt 3 / 2) * 20^2, no gaps, no overlaps.
    CHECK(double(ink) == Approx(7 * 1.5 * std::sqrt(3.0) * 400).epsilon(0.01));
    for (auto cell : flower) CHECK(inked(image, render::hex_centre(view, cell)));
}

TEST_CASE("neighbouring hexagon centres are sqrt 3 sizes apart with one arm straight up", "[hex]") {
    const render::HexView view{{0, 0}, 10};
    const glm::vec2 up = render::hex_centre(view, {0, 1});
    CHECK(up.x == Approx(0).margin(1e-5));
    CHECK(up.y == Approx(-10 * std::sqrt(3.0f)));  // y down: "up" is negative
    const glm::vec2 right = render::hex_centre(view, {1, 0});
    CHECK(glm::length(right) == Approx(10 * std::sqrt(3.0f)));
    CHECK(std::atan2(-right.y, right.x) == Approx(M_PI / 6));  // 30 degrees
}

TEST_CASE("fit_hex_view makes every cell of a radius fit the area", "[hex]") {
    const render::Rect area{10, 20, 300, 200};
    const int radius = 12;
    const render::HexView view = render::fit_hex_view(area, radius);
    // The six extreme cells, their hexagons included, stay inside the area.
    for (glm::ivec2 cell : {glm::ivec2{radius, 0}, glm::ivec2{-radius, 0}, glm::ivec2{0, radius},
                            glm::ivec2{0, -radius}, glm::ivec2{radius, -radius}, glm::ivec2{-radius, radius}}) {
        const glm::vec2 c = render::hex_centre(view, cell);
        CHECK(c.x - view.size >= area.x - 1e-3f);
        CHECK(c.x + view.size <= area.right() + 1e-3f);
        CHECK(c.y - view.size * std::sqrt(3.0f) / 2 >= area.y - 1e-3f);
        CHECK(c.y + view.size * std::sqrt(3.0f) / 2 <= area.bottom() + 1e-3f);
    }
    CHECK(view.centre == area.centre());
}
