#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gl/canvas.hpp"
#include "media/png_io.hpp"
#include "render/shapes.hpp"
#include "render/tubes.hpp"

using render::Camera;
using render::Light;
using render::Tube;

namespace {

const glm::vec4 black{0, 0, 0, 1}, white{1, 1, 1, 1};
const Light flat{{0, 1, 0}, 1, 0, 0};  // every pixel of a tube in exactly its colour

// How much of a pixel black ink covers on white, 0..1.
float ink(const render::Image& image, int x, int y) { return float(255 - image.pixel(x, y)[1]) / 255; }

Camera looking_from(glm::vec3 eye, float fov_degrees) {
    Camera camera;
    camera.eye = eye;
    camera.target = {0, 0, 0};
    camera.fov_degrees = fov_degrees;
    return camera;
}

// A tree in the manner of an L-system: each branch ends in three shorter,
// thinner ones, turned about the parent's axis by a different phase each
// generation and drawn slightly upwards.
void grow(std::vector<Tube>& tubes, glm::vec3 base, glm::vec3 direction, float length, float radius, int depth,
          int generations) {
    const glm::vec3 tip = base + direction * length;
    const float shade = float(depth) / float(generations);
    const glm::vec4 bark{0.58f, 0.40f, 0.26f, 1}, leaf{0.42f, 0.76f, 0.30f, 1};
    tubes.push_back({base, tip, radius, radius * 0.7f, glm::mix(bark, leaf, shade * shade)});
    if (depth == generations) return;
    const glm::vec3 u = glm::normalize(glm::cross(std::abs(direction.y) < 0.9f ? glm::vec3(0, 1, 0)
                                                                               : glm::vec3(1, 0, 0), direction));
    const glm::vec3 v = glm::cross(direction, u);
    for (int k = 0; k < 3; ++k) {
        const float turn = 2 * std::numbers::pi_v<float> * (float(k) / 3 + 0.29f * float(depth));
        const float tilt = glm::radians(k == 0 ? 22.0f : 38.0f + 4.0f * float(k));
        const glm::vec3 sideways = std::cos(turn) * u + std::sin(turn) * v;
        const glm::vec3 child =
            glm::normalize(std::cos(tilt) * direction + std::sin(tilt) * sideways + glm::vec3(0, 0.15f, 0));
        grow(tubes, tip, child, length * (k == 0 ? 0.8f : 0.68f), radius * 0.7f, depth + 1, generations);
    }
}

}  // namespace

TEST_CASE("a vertical tube seen from the side is a centred band as wide as perspective says", "[tubes]") {
    render::Canvas canvas(300, 240, 4, true);
    canvas.clear(white);
    const render::Rect viewport{40, 30, 200, 180};
    const float radius = 2, distance = 5, fov = 60;
    const Camera camera = looking_from({0, 0, distance}, fov);
    render::draw_tubes(canvas, viewport, {{{0, -10, 0}, {0, 10, 0}, radius, radius, black}}, camera, flat, 64);
    const render::Image image = canvas.read();
    const int row = int(viewport.centre().y);
    double sum = 0, moment = 0;
    for (int x = 0; x < image.width; ++x) {
        sum += ink(image, x, row);
        moment += ink(image, x, row) * (x + 0.5);
    }
    CHECK(moment / sum == Approx(viewport.centre().x).margin(1));
    // The lines of sight touching the cylinder meet its axis plane at
    // r D / sqrt(D^2 - r^2) from the axis, wider than r: the eye sees less
    // than half the round. The viewport spans 2 D tan(fov / 2) at that plane.
    const double half = radius / std::sqrt(distance * distance - radius * radius);
    const double expected = 2 * half / std::tan(glm::radians(fov) / 2) * viewport.h / 2;
    CHECK(sum == Approx(expected).margin(1));
    // The band stops at the viewport although the tube goes on.
    for (int x = 0; x < image.width; ++x) {
        CHECK(ink(image, x, int(viewport.y) - 2) == 0);
        CHECK(ink(image, x, int(viewport.bottom()) + 1) == 0);
    }
    for (int y = 0; y < image.height; ++y) CHECK(ink(image, 20, y) == 0);
}

TEST_CASE("world y points up in the picture and project agrees with the drawing", "[tubes]") {
    render::Canvas canvas(200, 160, 4, true);
    canvas.clear(white);
    const render::Rect viewport{20, 10, 160, 140};
    const Camera camera = looking_from({0, 0, 12}, 35);
    const glm::vec3 a{1.5f, 1, 0}, b{1.5f, 2, 0};
    render::draw_tubes(canvas, viewport, {{a, b, 0.15f, 0.15f, black}}, camera, flat);
    const render::Image image = canvas.read();
    double sum = 0;
    glm::dvec2 moment{0, 0};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            sum += ink(image, x, y);
            moment += double(ink(image, x, y)) * glm::dvec2(x + 0.5, y + 0.5);
        }
    REQUIRE(sum > 0);
    const glm::dvec2 centroid = moment / sum;
    CHECK(centroid.x > viewport.centre().x);  // right of the axis
    CHECK(centroid.y < viewport.centre().y);  // above it, in y-down pixels
    const glm::vec2 expected = render::project(camera, viewport, (a + b) / 2.0f);
    CHECK(centroid.x == Approx(expected.x).margin(0.5));
    CHECK(centroid.y == Approx(expected.y).margin(0.5));
}

TEST_CASE("a nearer tube hides a farther one whichever is drawn first", "[tubes]") {
    const glm::vec4 red{1, 0, 0, 1}, blue{0, 0, 1, 1};
    const Tube near{{-3, 0, 1}, {3, 0, 1}, 0.5f, 0.5f, red};  // across, in front
    const Tube far{{0, -3, -1}, {0, 3, -1}, 0.5f, 0.5f, blue};  // upright, behind
    const Camera camera = looking_from({0, 0, 10}, 40);
    for (const auto& tubes : {std::vector<Tube>{near, far}, std::vector<Tube>{far, near}}) {
        render::Canvas canvas(120, 120, 4, true);
        canvas.clear(white);
        render::draw_tubes(canvas, {0, 0, 120, 120}, tubes, camera, flat);
        const render::Image image = canvas.read();
        const auto* crossing = image.pixel(60, 60);
        CHECK(int(crossing[0]) == 255);
        CHECK(int(crossing[2]) == 0);
        const auto* above = image.pixel(60, 25);  // the far tube where nothing is in front of it
        CHECK(int(above[0]) == 0);
        CHECK(int(above[2]) == 255);
    }
}

TEST_CASE("the side of a tube facing the light is brighter than the side away from it", "[tubes]") {
    render::Canvas canvas(160, 160, 4, true);
    canvas.clear(white);
    const Light from_the_right{{1, 0, 0}, 0.3f, 0.7f, 0};
    const glm::vec4 grey{0.6f, 0.6f, 0.6f, 1};
    const Camera camera = looking_from({0, 0, 10}, 35);
    render::draw_tubes(canvas, {0, 0, 160, 160}, {{{0, -5, 0}, {0, 5, 0}, 1, 1, grey}}, camera, from_the_right, 32);
    const render::Image image = canvas.read();
    const glm::vec2 centre = render::project(camera, {0, 0, 160, 160}, {0, 0, 0});
    const glm::vec2 right = render::project(camera, {0, 0, 160, 160}, {0.7f, 0, 0.7f});
    const float offset = right.x - centre.x;
    const int lit = image.pixel(int(centre.x + offset), 80)[0], unlit = image.pixel(int(centre.x - offset), 80)[0];
    CHECK(lit > unlit + 60);
    // Away from the light only the ambient share is left.
    CHECK(unlit == Approx(0.3 * 0.6 * 255).margin(2));
}

TEST_CASE("frame_bounds keeps every corner of the box inside the viewport and fills it", "[tubes]") {
    const glm::vec3 lo{-3, 0, -1}, hi{5, 10, 2};
    for (const float azimuth : {0.0f, 30.0f, 135.0f, -100.0f})
        for (const float elevation : {0.0f, 25.0f, 60.0f, 90.0f, -40.0f})
            for (const float aspect : {0.5f, 1.0f, 2.0f}) {
                INFO("azimuth " << azimuth << " elevation " << elevation << " aspect " << aspect);
                const Camera camera = render::frame_bounds(lo, hi, azimuth, elevation, aspect);
                CHECK(camera.target == (lo + hi) / 2.0f);
                const glm::mat4 m = glm::perspective(glm::radians(camera.fov_degrees), aspect, camera.near, camera.far) *
                                    glm::lookAt(camera.eye, camera.target, camera.up);
                float widest = 0;
                for (int i = 0; i < 8; ++i) {
                    const glm::vec4 clip =
                        m * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1);
                    REQUIRE(clip.w > 0);  // in front of the eye
                    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                    CHECK(std::abs(ndc.x) <= 1);
                    CHECK(std::abs(ndc.y) <= 1);
                    CHECK(std::abs(ndc.z) <= 1);  // between near and far
                    widest = std::max({widest, std::abs(ndc.x), std::abs(ndc.y)});
                }
                CHECK(widest > 0.9f);  // fitted, not merely far away
            }
}

TEST_CASE("draw_tubes refuses a canvas without a depth buffer", "[tubes]") {
    render::Canvas flat_canvas(50, 50);
    CHECK_FALSE(flat_canvas.has_depth());
    const Camera camera = looking_from({0, 0, 10}, 35);
    CHECK_THROWS_AS(render::draw_tubes(flat_canvas, {0, 0, 50, 50}, {}, camera), std::logic_error);
    render::Canvas deep(50, 50, 4, true);
    CHECK(deep.has_depth());
    CHECK_THROWS_AS(render::draw_tubes(deep, {0, 0, 50, 50}, {{{0, 0, 0}, {0, 1, 0}, -1, 1, black}}, camera),
                    std::invalid_argument);
}

TEST_CASE("2-D shapes drawn after draw_tubes land where expected", "[tubes]") {
    render::Canvas canvas(160, 120, 4, true);
    canvas.clear(white);
    // A fat tube filling the right half's viewport.
    render::draw_tubes(canvas, {80, 0, 80, 120}, {{{0, -9, 0}, {0, 9, 0}, 3, 3, black}},
                       looking_from({0, 0, 6}, 35), flat);
    CHECK_FALSE(glIsEnabled(GL_DEPTH_TEST));
    CHECK_FALSE(glIsEnabled(GL_SCISSOR_TEST));
    CHECK_FALSE(glIsEnabled(GL_CULL_FACE));
    render::Shapes shapes;
    shapes.rect({100, 50, 20, 20}, {1, 0, 0, 1});  // over the tube: no depth test hides it
    shapes.rect({10, 10, 20, 20}, {0, 1, 0, 1});   // outside the tubes' viewport: no scissor clips it
    shapes.draw(canvas);
    const render::Image image = canvas.read();
    CHECK(int(image.pixel(110, 60)[0]) == 255);
    CHECK(int(image.pixel(110, 60)[1]) == 0);
    CHECK(int(image.pixel(20, 20)[1]) == 255);
    CHECK(int(image.pixel(20, 20)[0]) == 0);
    CHECK(int(image.pixel(100, 60)[0]) == 255);  // the rect's left edge stays at x = 100
    CHECK(int(image.pixel(99, 60)[0]) == 0);     // and the tube is still there beside it
    CHECK(int(image.pixel(20, 9)[0]) == 255);    // its top edge at y = 10 in pixel space
}

TEST_CASE("a bent branch has a round joint with no notch at the outer corner", "[tubes]") {
    render::Canvas canvas(160, 160, 4, true);
    canvas.clear(white);
    const render::Rect viewport{0, 0, 160, 160};
    const Camera camera = looking_from({1, 1, 12}, 35);
    const float r = 0.5f;
    render::draw_tubes(canvas, viewport, {{{0, -1, 0}, {0, 2, 0}, r, r, black}, {{0, 2, 0}, {3, 2, 0}, r, r, black}},
                       camera, flat);
    const render::Image image = canvas.read();
    // Square-cut cylinders would leave the outer corner's quarter disc empty.
    const glm::vec2 corner = render::project(camera, viewport, {-0.6f * r, 2 + 0.6f * r, 0});
    CHECK(ink(image, int(corner.x), int(corner.y)) == 1);
    const glm::vec2 outside = render::project(camera, viewport, {-0.8f * r, 2 + 0.8f * r, 0});
    CHECK(ink(image, int(outside.x), int(outside.y)) == 0);  // round, not square
}

TEST_CASE("a branching plant of a few hundred tubes is framed whole", "[tubes]") {
    std::vector<Tube> plant;
    grow(plant, {0, 0, 0}, {0, 1, 0}, 3, 0.28f, 0, 5);
    REQUIRE(plant.size() == 364);
    const int size = 600;
    render::Canvas canvas(size, size, 4, true);
    canvas.clear(white);
    const auto [lo, hi] = render::tube_bounds(plant);
    const Camera camera = render::frame_bounds(lo, hi, -25, 15, 1);
    render::draw_tubes(canvas, {0, 0, float(size), float(size)}, plant, camera);
    const render::Image image = canvas.read();
    media::write_png(std::filesystem::temp_directory_path() / "figgen-tubes-plant.png", image);
    int left = size, right = -1, top = size, bottom = -1;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            if (image.pixel(x, y)[2] < 250) {
                left = std::min(left, x), right = std::max(right, x);
                top = std::min(top, y), bottom = std::max(bottom, y);
            }
    // Whole (nothing touches the edges) and large (it fills most of one side).
    CHECK(left > 2);
    CHECK(top > 2);
    CHECK(right < size - 3);
    CHECK(bottom < size - 3);
    CHECK(std::max(right - left, bottom - top) > size / 2);
}


TEST_CASE("frame_balls centres the balls and fills the tighter side of the viewport", "[tubes]") {
    // A tall cloud of balls off the origin, some with radii.
    std::vector<render::Ball> balls;
    for (int k = 0; k < 40; ++k) {
        const float t = float(k) / 39;
        balls.push_back({{4 + 3 * std::sin(7.0f * t), 10 + 20 * t, -2 + 4 * std::cos(5.0f * t)}, 0.3f * t});
    }
    for (const float azimuth : {0.0f, 30.0f, 150.0f, -100.0f})
        for (const float elevation : {0.0f, 12.0f, 60.0f, -40.0f})
            for (const float aspect : {0.5f, 1.0f, 2.5f}) {
                INFO("azimuth " << azimuth << " elevation " << elevation << " aspect " << aspect);
                const Camera camera = render::frame_balls(balls, azimuth, elevation, aspect, 0.9f);
                const render::Extent e = render::projected_extent(balls, camera, aspect);
                // Centred, inside, and one side filled to 0.9.
                CHECK(std::abs(e.lo.x + e.hi.x) < 0.01f);
                CHECK(std::abs(e.lo.y + e.hi.y) < 0.01f);
                CHECK(std::max(e.hi.x, e.hi.y) == Approx(0.9f).margin(0.01f));
                // The centres land where GL puts them, inside the viewport and between near and far.
                const glm::mat4 m = render::view_projection(camera, aspect);
                for (const render::Ball& b : balls) {
                    const glm::vec4 clip = m * glm::vec4(b.centre, 1);
                    REQUIRE(clip.w > 0);
                    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                    CHECK(ndc.x >= e.lo.x - 1e-4f);
                    CHECK(ndc.x <= e.hi.x + 1e-4f);
                    CHECK(ndc.y >= e.lo.y - 1e-4f);
                    CHECK(ndc.y <= e.hi.y + 1e-4f);
                    CHECK(std::abs(ndc.z) <= 1);
                }
                // Kept back: the balls shrink about the centre.
                const float d = glm::length(camera.eye - camera.target);
                const Camera far = render::frame_balls(balls, azimuth, elevation, aspect, 0.9f, 2 * d);
                CHECK(glm::length(far.eye - far.target) == Approx(2 * d));
                const render::Extent f = render::projected_extent(balls, far, aspect);
                CHECK(std::max(f.hi.x, f.hi.y) < 0.6f);
                CHECK(std::abs(f.lo.y + f.hi.y) < 0.01f);
            }
}

TEST_CASE("a facet is lit on the side the eye sees and hides a tube behind it", "[tubes]") {
    render::Canvas canvas(100, 100, 4, true);
    const glm::vec4 green{0.2f, 0.6f, 0.2f, 1}, red{0.8f, 0.1f, 0.1f, 1};
    // A square in z = 0 facing +z, two triangles wound one way, and a red tube behind it.
    const std::vector<render::Facet> square = {{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, green},
                                               {{-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, green}};
    const std::vector<Tube> behind = {{{0, -3, -1}, {0, 3, -1}, 0.3f, 0.3f, red}};
    const Light head_on{{0, 0, 1}, 0.3f, 0.7f, 0};
    const Light head_on_back{{0, 0, -1}, 0.3f, 0.7f, 0};
    for (const float z : {5.0f, -5.0f}) {
        INFO("eye at z = " << z);
        canvas.clear(white);
        Camera camera = looking_from({0, 0, z}, 40);
        render::draw_tubes(canvas, {0, 0, 100, 100}, behind, square, camera, z > 0 ? head_on : head_on_back);
        const render::Image image = canvas.read();
        // Beside the tube: the leaf, fully lit from the eye's side (ambient + diffuse = 1) whichever side it is.
        const auto middle = image.pixel(30, 50);
        CHECK(int(middle[0]) == Approx(0.2 * 255).margin(2));
        CHECK(int(middle[1]) == Approx(0.6 * 255).margin(2));
        if (z > 0) {
            // The tube shows above and below the square, and not through it.
            CHECK(int(image.pixel(50, 5)[0]) > 150);
            CHECK(int(image.pixel(50, 5)[1]) < 100);
        }
    }
    // A facet with no area, or none at all, draws nothing and is no error.
    canvas.clear(white);
    render::draw_tubes(canvas, {0, 0, 100, 100}, {}, {{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, green}},
                       looking_from({0, 0, 5}, 40));
    CHECK(canvas.read().pixel(50, 50)[0] == 255);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_AS(render::draw_tubes(canvas, {0, 0, 100, 100}, {}, {{{0, 0, 0}, {1, 0, 0}, {0, nan, 0}, green}},
                                       looking_from({0, 0, 5}, 40)),
                    std::invalid_argument);
}
