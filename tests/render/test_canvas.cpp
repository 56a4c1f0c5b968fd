#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <vector>

#include "render/gl/canvas.hpp"
#include "render/gl/gl_context.hpp"
#include "render/shapes.hpp"

using render::Canvas;

TEST_CASE("the OSMesa context is core profile 3.3 or later with 4x multisampling") {
    const auto& gl = render::GlContext::get();
    int major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    CHECK(major * 10 + minor >= 33);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    CHECK((profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0);
    CHECK(gl.max_samples() >= 4);
    CHECK(&render::GlContext::get() == &gl);  // one context per process
}

TEST_CASE("a filled rectangle lands on the pixels it covers, top-left origin") {
    Canvas canvas(40, 30);
    CHECK(canvas.samples() == 4);
    canvas.clear({1, 1, 1, 1});
    render::Shapes shapes;
    shapes.rect({10, 5, 20, 10}, {1, 0, 0, 1});  // x 10..30, y 5..15
    shapes.draw(canvas);
    const render::Image image = canvas.read();
    REQUIRE(image.width == 40);
    REQUIRE(image.height == 30);
    const auto* inside = image.pixel(20, 10);
    CHECK(int(inside[0]) == 255);
    CHECK(int(inside[1]) == 0);
    CHECK(int(inside[3]) == 255);
    const auto* above = image.pixel(20, 4);  // white background above the rectangle
    CHECK(int(above[1]) == 255);
    const auto* below = image.pixel(20, 15);
    CHECK(int(below[1]) == 255);
}

TEST_CASE("a one-sample canvas is a plain framebuffer and not the smallest multisampled one Mesa has") {
    render::Canvas one(40, 30, 1), four(40, 30, 4);
    CHECK(one.samples() == 1);
    CHECK(four.samples() == 4);
    // Asked for 1 sample, glRenderbufferStorageMultisample gives llvmpipe's
    // 4; a plain renderbuffer has none. A diagonal edge shows which it got:
    // one sample per pixel leaves only fully on or off pixels.
    for (render::Canvas* canvas : {&one, &four}) {
        canvas->clear({1, 1, 1, 1});
        render::Shapes shapes;
        shapes.triangle({0, 0}, {40, 0}, {0, 30}, {0, 0, 0, 1});
        shapes.draw(*canvas);
    }
    auto partial = [](const render::Image& image) {
        int count = 0;
        for (std::size_t i = 0; i < image.rgba.size(); i += 4) count += image.rgba[i] != 0 && image.rgba[i] != 255;
        return count;
    };
    CHECK(partial(one.read()) == 0);
    CHECK(partial(four.read()) > 20);  // the edge's pixels, about one per row
}

TEST_CASE("a canvas that takes over a destroyed one's buffers starts as empty as a new one", "[canvas]") {
    // A canvas of the size and kind of one just destroyed reuses its GL
    // objects (canvas.cpp); what was drawn there must not show through.
    auto draw_and_read = [](bool depth) {
        Canvas canvas(37, 23, 4, depth);
        const render::Image before = canvas.read();
        canvas.clear({0.2f, 0.4f, 0.6f, 1});
        render::Shapes shapes;
        shapes.rect({3, 3, 20, 10}, {1, 0, 0, 1});
        shapes.draw(canvas);
        CHECK(canvas.read().pixel(10, 8)[0] == 255);
        return before;
    };
    for (bool depth : {false, true}) {
        const render::Image first = draw_and_read(depth), second = draw_and_read(depth);
        const render::Image blank(37, 23);  // zero: transparent black
        CHECK(first.rgba == blank.rgba);
        CHECK(second.rgba == blank.rgba);
    }
    // A different size does not take them: it gets its own size.
    Canvas other(41, 23);
    CHECK(other.read().width == 41);
    CHECK(other.read().rgba == render::Image(41, 23).rgba);
}

TEST_CASE("frames read back through pixel buffers are the frames read directly, in order", "[canvas]") {
    // Each frame a different colour and a moving square; read three deep, so
    // that frame n is taken after n + 1 and n + 2 were drawn on the same canvas.
    render::Canvas canvas(64, 40);
    const auto paint = [&](int i) {
        canvas.clear({0.1f * float(i % 10), 0.5f, 1.0f - 0.05f * float(i), 1.0f});
        render::Shapes shapes;
        shapes.rect({float(3 * i), 10, 12, 12}, {1, 1, 0, 1});
        shapes.draw(canvas);
    };
    std::vector<render::Image> direct, through;
    render::FrameReader reader(3);
    for (int i = 0; i < 12; ++i) {
        paint(i);
        direct.push_back(canvas.read());
        if (auto image = reader.read(canvas)) through.push_back(std::move(*image));
        CHECK(reader.in_flight() == std::min(i + 1, 2));
    }
    while (auto image = reader.next()) through.push_back(std::move(*image));
    CHECK(reader.in_flight() == 0);
    REQUIRE(through.size() == direct.size());
    for (std::size_t i = 0; i < direct.size(); ++i) {
        INFO("frame " << i);
        CHECK(through[i].width == 64);
        CHECK(through[i].height == 40);
        CHECK(through[i].rgba == direct[i].rgba);
    }
    CHECK(direct[0].rgba != direct[1].rgba);
    // A transparent canvas's frames come back with straight alpha, as read() gives them.
    render::Canvas clear(32, 32);
    clear.set_transparent(true);
    clear.background({1, 1, 1, 1});
    render::Shapes half;
    half.rect({4, 4, 20, 20}, {0.8f, 0.2f, 0.4f, 0.5f});
    half.draw(clear);
    render::FrameReader one(1);
    const std::optional<render::Image> read = one.read(clear);
    REQUIRE(read);
    CHECK(read->rgba == clear.read().rgba);
}
