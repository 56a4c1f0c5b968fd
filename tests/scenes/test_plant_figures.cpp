// The pl figures as a user drives them, and the numbers they record.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "render/image.hpp"
#include "media/png_io.hpp"

namespace fs = std::filesystem;

namespace {
std::filesystem::path out_dir(const std::string& name) { return testkit::fresh_dir("plants-" + name); }
}  // namespace

using testkit::figgen;
using testkit::render_json;
using testkit::Run;

TEST_CASE("the club moss draws the article's 6 (6^n - 1) / 5 segments", "[plants]") {
    const auto meta = render_json("pl-lsys-lycopodium", "");
    REQUIRE(meta["panels"].size() == 1);
    CHECK(meta["panels"][0]["segments"] == 6 * (216 - 1) / 5);  // depth 3: 258
    CHECK(meta["panels"][0]["reading"] == "article");
}

TEST_CASE("an L-system rule can be given on the command line", "[plants]") {
    // F -> FF doubles: 2^n segments in the rewrite reading.
    const auto meta = render_json("pl-lsys-lycopodium", "--set 'rule=F -> FF' --set reading=rewrite --set depth=5");
    CHECK(meta["panels"][0]["segments"] == 32);
    CHECK(meta["panels"][0]["plant"]["rules"] == nlohmann::json::array({"F -> FF"}));
}

TEST_CASE("malformed L-system rules are refused with one line naming the problem", "[plants]") {
    for (const char* bad : {"'rule=F -> F[+F'", "'rule=FF -> F'", "'rule=F FF'", "'rule=F -> F#'"}) {
        INFO(bad);
        const Run run = figgen(std::string("render pl-lsys-lycopodium --no-video --out ") +
                               out_dir("bad").string() + " --set " + bad);
        CHECK(run.status == 2);
        CHECK_THAT(run.output, Catch::StartsWith("figgen: error: "));
        CHECK(std::count(run.output.begin(), run.output.end(), '\n') == 1);
    }
    // Within the turtle's budget, the memory estimate refuses what does not fit.
    const Run deep = figgen("render pl-lsys-lycopodium --no-video --out " + out_dir("deep").string() +
                            " --set depth=7 --max-memory 1M");
    CHECK(deep.status == 2);
    CHECK_THAT(deep.output, Catch::Contains("of memory (plant of depth 7, 335922 segments: ") &&
                                Catch::Contains("more than --max-memory 1.0 MiB"));
    // Beyond it, the budget refuses it in phase 1, whatever the memory.
    const Run budget = figgen("render pl-lsys-lycopodium --no-video --out " + out_dir("deep").string() +
                              " --set depth=12 --max-memory 1000G");
    CHECK(budget.status == 2);
    CHECK_THAT(budget.output, Catch::Contains("segments, more than the budget of 800,000"));
}

TEST_CASE("the ABOP gallery draws the six plants with their closed-form segment counts", "[plants]") {
    const auto meta = render_json("pl-lsys-gallery", "");
    REQUIRE(meta["panels"].size() == 6);
    CHECK(meta["panels"][0]["segments"] == std::pow(5, 5));  // F -> F[+F]F[-F]F: 5 F per F
    CHECK(meta["panels"][1]["segments"] == std::pow(5, 5));  // F -> F[+F]F[-F][F]
    CHECK(meta["panels"][2]["segments"] == std::pow(8, 4));  // F -> FF-[-F+F+F]+[+F-F-F]: 8 F per F
}

TEST_CASE("the fern's points stay in the fern's known box", "[plants]") {
    const auto meta = render_json("pl-ifs-fern", "");
    // The published bounds of Barnsley's fern: -2.1820 < x < 2.6558, 0 <= y < 9.9983.
    const auto& bounds = meta["panels"][0]["points_bounds"];  // xmin, xmax, ymin, ymax
    CHECK(meta["panels"][0]["points"] == 200000);
    CHECK(bounds[0].get<double>() > -2.1821);
    CHECK(bounds[0].get<double>() < -2.0);
    CHECK(bounds[1].get<double>() < 2.6559);
    CHECK(bounds[1].get<double>() > 2.5);
    CHECK(bounds[2].get<double>() >= 0.0);
    CHECK(bounds[3].get<double>() < 9.9984);
    CHECK(bounds[3].get<double>() > 9.9);
    // The stem map (p = 0.01) is chosen about 1% of the time.
    const double stem = meta["panels"][0]["map_counts"][0].get<double>() / 200100.0;
    CHECK(stem == Approx(0.01).margin(0.002));
}

TEST_CASE("the sunflower places 240 seeds and 40 petals", "[plants]") {
    const auto meta = render_json("pl-phyllotaxis", "");
    REQUIRE(meta["panels"].size() == 3);
    CHECK(meta["panels"][0]["seeds"] == 240);
    CHECK(meta["panels"][0]["petals"] == 40);
    CHECK(meta["panels"][0]["outer_radius"].get<double>() == Approx(7 * std::sqrt(239.0)));
}

namespace {

// The least box (x0, y0, x1, y1, pixels, ends exclusive) of the pixels in
// `r` that are not white: the plant's ink. Empty (x0 >= x1) when none.
struct InkBox {
    int x0, y0, x1, y1;
};
InkBox ink_in(const render::Image& image, int left, int top, int right, int bottom) {
    InkBox box{right, bottom, left, top};
    for (int y = top; y < bottom; ++y)
        for (int x = left; x < right; ++x) {
            const std::uint8_t* p = image.pixel(x, y);
            if (p[0] < 245 || p[1] < 245 || p[2] < 245) {
                box.x0 = std::min(box.x0, x), box.y0 = std::min(box.y0, y);
                box.x1 = std::max(box.x1, x + 1), box.y1 = std::max(box.y1, y + 1);
            }
        }
    return box;
}

}  // namespace

TEST_CASE("the 3-D plant fills at least 80% of its panels' height and stays inside them", "[plants][lsys-3d]") {
    // The figure at the golden's scale, and a film of 12 frames (a turn in 30 degree steps) as PNGs.
    const fs::path out = out_dir("lsys-3d-fill");
    const Run run = figgen("render pl-lsys-3d --no-video --frames --scale 0.5 --set 'animation.steps=[0,11]' --out " +
                           out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    const render::Image figure = media::read_png(out / "pl-lsys-3d.png").image;
    std::ifstream in(out / "pl-lsys-3d.json");
    const nlohmann::json meta = nlohmann::json::parse(in);
    CHECK(meta["polygons"].get<int>() > 1000);  // the leaves are there
    REQUIRE(meta["panels"].size() == 2);
    for (const auto& panel : meta["panels"]) {
        INFO("azimuth " << panel["azimuth_degrees"]);
        const auto& r = panel["rect"];
        const int left = int(std::lround(r[0].get<double>())), top = int(std::lround(r[1].get<double>()));
        const int right = int(std::lround(r[0].get<double>() + r[2].get<double>()));
        const int bottom = int(std::lround(r[1].get<double>() + r[3].get<double>()));
        const InkBox ink = ink_in(figure, left, top, right, bottom);
        const double fill = double(ink.y1 - ink.y0) / double(bottom - top);
        INFO("panel " << left << "," << top << " to " << right << "," << bottom << ": ink " << ink.x0 << ","
                      << ink.y0 << " to " << ink.x1 << "," << ink.y1 << ", height fill " << fill);
        CHECK(fill >= 0.8);
        // Not cut off at any edge of the panel.
        CHECK(ink.x0 > left);
        CHECK(ink.y0 > top);
        CHECK(ink.x1 < right);
        CHECK(ink.y1 < bottom);
        // The box the metadata gives is the one drawn, to a pixel or two.
        const auto& box = panel["plant_box"];
        CHECK(box[1].get<double>() == Approx(ink.y0).margin(2));
        CHECK(box[3].get<double>() == Approx(ink.y1).margin(2));
    }
    // Below and beside the panels: nothing.
    const auto& first = meta["panels"][0]["rect"];
    const int panels_bottom = int(std::lround(first[1].get<double>() + first[3].get<double>()));
    const InkBox below = ink_in(figure, 0, panels_bottom + 1, figure.width, figure.height);
    CHECK(below.x0 >= below.x1);

    int frames = 0;
    for (const auto& entry : fs::directory_iterator(out / "pl-lsys-3d-frames")) {
        if (entry.path().extension() != ".png") continue;
        ++frames;
        INFO(entry.path().filename().string());
        const render::Image frame = media::read_png(entry.path()).image;
        const InkBox ink = ink_in(frame, 0, 0, frame.width, frame.height);
        const double fill = double(ink.y1 - ink.y0) / double(frame.height);
        INFO("ink " << ink.x0 << "," << ink.y0 << " to " << ink.x1 << "," << ink.y1 << ", height fill " << fill);
        CHECK(fill >= 0.8);
        CHECK(ink.x0 > 0);
        CHECK(ink.y0 > 0);
        CHECK(ink.x1 < frame.width);
        CHECK(ink.y1 < frame.height);
    }
    CHECK(frames == 12);
}
