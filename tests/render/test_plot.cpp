#include <catch2/catch.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl/canvas.hpp"
#include "render/plot.hpp"
#include "render/shapes.hpp"
#include "render/ticks.hpp"

using namespace render;

namespace {

std::vector<double> values(const std::vector<Tick>& ticks) {
    std::vector<double> out;
    for (const Tick& t : ticks) out.push_back(t.value);
    return out;
}

std::vector<std::string> labels(const std::vector<Tick>& ticks) {
    std::vector<std::string> out;
    for (const Tick& t : ticks) out.push_back(t.label);
    return out;
}

void check_values(const std::vector<double>& actual, const std::vector<double>& expected) {
    REQUIRE(actual.size() == expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i) CHECK(actual[i] == Approx(expected[i]).epsilon(1e-12));
}

const glm::vec4 red{1, 0, 0, 1};

// Pixels that are clearly red: the marker or line under test, not the black ink of the axes.
bool is_red(const Image& image, int x, int y) {
    const auto* p = image.pixel(x, y);
    return p[0] > 200 && p[1] < 120 && p[2] < 120;
}

struct Blob {
    double x = 0, y = 0;  // centre, pixel edges (a pixel's centre is at +0.5)
    int count = 0;
    int left = INT_MAX, top = INT_MAX, right = INT_MIN, bottom = INT_MIN;
};

Blob red_ink(const Image& image) {
    Blob b;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (is_red(image, x, y)) {
                b.x += x + 0.5, b.y += y + 0.5, ++b.count;
                b.left = std::min(b.left, x), b.right = std::max(b.right, x);
                b.top = std::min(b.top, y), b.bottom = std::max(b.bottom, y);
            }
    if (b.count > 0) b.x /= b.count, b.y /= b.count;
    return b;
}

Image plot(const Axes& axes, const Rect& frame, int w = 400, int h = 300, const PlotStyle& style = {}) {
    Canvas canvas(w, h);
    canvas.clear({1, 1, 1, 1});
    draw_axes(canvas, frame, axes, style);
    return canvas.read();
}

Series marker_at(double x, double y) {
    Series s;
    s.x = {x};
    s.y = {y};
    s.colour = red;
    s.line_width = 0;
    s.marker_size = 8;
    return s;
}

}  // namespace

TEST_CASE("linear ticks are those of matplotlib's AutoLocator and ScalarFormatter", "[plot]") {
    const AxisTicks unit = linear_ticks(0, 1);
    check_values(values(unit.major), {0, 0.2, 0.4, 0.6, 0.8, 1.0});
    CHECK(labels(unit.major) == std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"});
    CHECK(unit.minor.empty());
    // With matplotlib's 5% margins the ticks stay on the round values inside.
    const auto [lo, hi] = linear_auto_range(0, 1);
    CHECK(lo == Approx(-0.05));
    CHECK(hi == Approx(1.05));
    CHECK(labels(linear_ticks(lo, hi).major) == labels(unit.major));

    const AxisTicks hundreds = linear_ticks(0, 500);
    check_values(values(hundreds.major), {0, 100, 200, 300, 400, 500});
    CHECK(labels(hundreds.major) == std::vector<std::string>{"0", "100", "200", "300", "400", "500"});
    // Steps of 2.5 x 10^k, one decimal for all; a minus sign, not a hyphen.
    CHECK(labels(linear_ticks(0, 10, 4).major) == std::vector<std::string>{"0.0", "2.5", "5.0", "7.5", "10.0"});
    CHECK(labels(linear_ticks(-1.1, 1.1).major) ==
          std::vector<std::string>{"\u22121.00", "\u22120.75", "\u22120.50", "\u22120.25", "0.00", "0.25", "0.50",
                                   "0.75", "1.00"});
    CHECK(labels(linear_ticks(-210, 2100, 5).major) ==
          std::vector<std::string>{"0", "500", "1000", "1500", "2000"});
    // Reversed limits give the same ticks; a single value gets ticks around it.
    CHECK(labels(linear_ticks(500, 0).major) == labels(hundreds.major));
    CHECK(linear_ticks(3, 3).major.size() >= 2);
    CHECK_THROWS_AS(linear_ticks(0, INFINITY), std::invalid_argument);
}

TEST_CASE("tick bins follow matplotlib's tick space for the axis length", "[plot]") {
    CHECK(tick_bins(205, 14, true) == 4);    // a third of a 900-pixel page across
    CHECK(tick_bins(340, 14, false) == 9);   // its height: capped at 9
    CHECK(tick_bins(20, 14, true) == 1);
    // On a short axis fewer, coarser ticks.
    CHECK(linear_ticks(0, 1, 2).major.size() == 3);  // 0.0 0.5 1.0
}

TEST_CASE("log ticks are powers of ten with minor ticks at 2 to 9 times them", "[plot]") {
    const AxisTicks t = log_ticks(1, 600);
    check_values(values(t.major), {1, 10, 100});
    CHECK(labels(t.major) == std::vector<std::string>{"10\u2070", "10\u00b9", "10\u00b2"});
    // matplotlib keeps a tick on the edge of the view: 600 is one.
    check_values(values(t.minor), {2, 3, 4, 5, 6, 7, 8, 9, 20, 30, 40, 50, 60, 70, 80, 90, 200, 300, 400, 500, 600});
    for (const Tick& m : t.minor) CHECK(m.label.empty());
    const AxisTicks below = log_ticks(1, 550);
    CHECK(values(below.minor).back() == Approx(500));
    CHECK(below.minor.size() == 20);

    CHECK(power_of_ten_label(-3) == "10\u207b\u00b3");
    CHECK(power_of_ten_label(5) == "10\u2075");
    CHECK(power_of_ten_label(12) == "10\u00b9\u00b2");
}

TEST_CASE("a log axis over many decades labels every second or third one", "[plot]") {
    // Eight decades where four ticks fit: every third, minor ticks at the others.
    const AxisTicks t = log_ticks(1, 1e8, 4);
    check_values(values(t.major), {1, 1e3, 1e6});
    check_values(values(t.minor), {10, 100, 1e4, 1e5, 1e7, 1e8});
    // Fifteen decades where nine fit: every second, and no minor ticks past ten decades.
    const AxisTicks wide = log_ticks(1e-3, 1e12, 9);
    check_values(values(wide.major), {1e-2, 1, 1e2, 1e4, 1e6, 1e8, 1e10, 1e12});
    CHECK(wide.minor.empty());
    // Less than a decade: the minor ticks carry the labels, as "3×10⁰".
    const AxisTicks narrow = log_ticks(2, 9);
    CHECK(narrow.major.empty());
    REQUIRE(narrow.minor.size() == 8);
    CHECK(narrow.minor[1].label == "3\u00d710\u2070");
    CHECK_THROWS_AS(log_ticks(0, 10), std::invalid_argument);
    CHECK_THROWS_AS(log_ticks(-1, 10), std::invalid_argument);
}

TEST_CASE("automatic ranges add 5 percent margins in linear or log space", "[plot]") {
    const auto [a, b] = linear_auto_range(0, 10);
    CHECK(a == Approx(-0.5));
    CHECK(b == Approx(10.5));
    const auto [c, d] = log_auto_range(1, 1e4);
    CHECK(c == Approx(std::pow(10.0, -0.2)));
    CHECK(d == Approx(std::pow(10.0, 4.2)));
    const auto [e, f] = linear_auto_range(2, 2);
    CHECK(e < 2);
    CHECK(f > 2);
    CHECK_THROWS_AS(log_auto_range(0, 5), std::invalid_argument);
}

TEST_CASE("a data point lands on its pixel on log and linear axes", "[plot]") {
    const Rect frame{50, 40, 300, 200};
    Axes log_axes;
    log_axes.x_scale = log_axes.y_scale = Scale::log;
    log_axes.x_range = std::pair{1.0, 1000.0};
    log_axes.y_range = std::pair{1.0, 1e4};
    log_axes.series = {marker_at(10, 100)};  // a third across, half way up
    const Blob on_log = red_ink(plot(log_axes, frame));
    REQUIRE(on_log.count > 20);
    CHECK(on_log.x == Approx(150).margin(1));
    CHECK(on_log.y == Approx(140).margin(1));
    const float rim = PlotStyle{}.marker_edge;  // matplotlib's marker edge, half of it outside the disc
    CHECK(on_log.right - on_log.left + 1 == Approx(8 + rim).margin(1.5));  // diameter 8 at scale 1

    Axes linear;
    linear.x_range = std::pair{0.0, 10.0};
    linear.y_range = std::pair{0.0, 1.0};
    linear.series = {marker_at(2.5, 0.75)};
    const Blob on_linear = red_ink(plot(linear, frame));
    CHECK(on_linear.x == Approx(125).margin(1));
    CHECK(on_linear.y == Approx(90).margin(1));

    // The style's scale scales the marker, not where it goes.
    PlotStyle big;
    big.scale = 2;
    const Blob scaled = red_ink(plot(linear, frame, 400, 300, big));
    CHECK(scaled.x == Approx(125).margin(1));
    CHECK(scaled.right - scaled.left + 1 == Approx(2 * (8 + rim)).margin(1.5));
}

TEST_CASE("major ticks sit under their values and point outwards", "[plot]") {
    const Rect frame{50, 40, 300, 200};
    Axes axes;
    axes.x_scale = Scale::log;
    axes.x_range = std::pair{1.0, 1000.0};
    axes.y_range = std::pair{0.0, 1.0};
    const Image image = plot(axes, frame);
    const int below = 240 + 3;  // under the bottom spine, inside a major tick's 4.9 pixels
    auto dark = [&](int x, int y) { return image.pixel(x, y)[1] < 100; };
    for (int x : {50, 150, 250}) CHECK(dark(x, below));  // 10⁰, 10¹, 10²
    CHECK_FALSE(dark(100, below));                      // between 10⁰ and 2 x 10⁰: nothing
    CHECK(dark(int(50 + 100 * std::log10(2.0)), 241));  // a minor tick at 2, shorter
    CHECK_FALSE(dark(int(50 + 100 * std::log10(2.0)), below + 1));
    for (int y : {240, 120, 40}) CHECK(dark(47, y));  // y ticks 0.0, 0.6, 1.0 (steps of 0.2) left of the spine
    CHECK_FALSE(dark(47, 140));                       // none at 0.5
    CHECK_FALSE(dark(52, 120));                       // nor inside the frame
}

TEST_CASE("a dashed line has gaps of the pattern's lengths across its vertices", "[plot]") {
    const Rect frame{20, 20, 360, 100};
    for (int points : {2, 37}) {  // one segment, or many in a row: the same dashes
        Axes axes;
        axes.x_range = std::pair{0.0, 1.0};
        axes.y_range = std::pair{0.0, 1.0};
        Series s;
        for (int i = 0; i < points; ++i) s.x.push_back(double(i) / (points - 1)), s.y.push_back(0.5);
        s.colour = red;
        s.line_width = 3;
        s.dash = {12, 6};
        axes.series = {s};
        const Image image = plot(axes, frame, 400, 140);
        std::vector<int> on, off;  // run lengths along the line's row, inside the frame
        bool inked = is_red(image, 22, 70);
        int run = 0;
        for (int x = 22; x < 378; ++x) {
            if (is_red(image, x, 70) == inked) {
                ++run;
                continue;
            }
            (inked ? on : off).push_back(run);
            inked = !inked, run = 1;
        }
        INFO(points << " points");
        REQUIRE(on.size() >= 18);  // 356 pixels / 18 per period, less the partial ends
        REQUIRE(off.size() >= 18);
        for (std::size_t i = 1; i < on.size(); ++i) CHECK(on[i] == Approx(12).margin(1.5));
        for (std::size_t i = 1; i < off.size(); ++i) CHECK(off[i] == Approx(6).margin(1.5));
        const Blob ink = red_ink(image);
        CHECK(ink.bottom - ink.top + 1 == Approx(3).margin(1));
    }
}

TEST_CASE("lines and markers are clipped to the frame", "[plot]") {
    const Rect frame{60, 50, 200, 150};
    Axes axes;
    axes.x_range = std::pair{0.0, 10.0};
    axes.y_range = std::pair{0.0, 10.0};
    Series s;
    s.x = {-20, 5, 30, 5, 1e300};  // far out, in and back, and absurdly far
    s.y = {-20, 5, 8, 20, 5};
    s.colour = red;
    s.line_width = 8;
    s.marker_size = 14;
    axes.series = {s, marker_at(0, 5), marker_at(10, 10)};  // markers centred on the spines
    const Image image = plot(axes, frame, 320, 260);
    const Blob ink = red_ink(image);
    REQUIRE(ink.count > 500);
    CHECK(ink.left >= 60);
    CHECK(ink.right <= 260);
    CHECK(ink.top >= 50);
    CHECK(ink.bottom <= 200);
    CHECK(ink.left <= 61);  // the marker on the left spine shows its right half
    CHECK(ink.top <= 51);
}

TEST_CASE("a translucent line that crosses itself keeps one shade", "[plot]") {
    Axes axes;
    axes.x_range = std::pair{0.0, 10.0};
    axes.y_range = std::pair{0.0, 10.0};
    Series s;
    s.x = {1, 9, 1, 9, 5, 5};  // doubles back over itself, then crosses
    s.y = {5, 5.2, 5.4, 5.6, 1, 9};
    for (int i = 0; i < 200; ++i) s.x.push_back(2 + 0.02 * i), s.y.push_back(2 + (i % 2) * 0.05);  // a fine zigzag
    s.colour = {0, 0, 1, 0.5f};
    s.line_width = 6;
    axes.series = {s};
    const Image image = plot(axes, {20, 20, 260, 260}, 300, 300);
    int darkest = 255;
    for (int y = 25; y < 275; ++y)
        for (int x = 25; x < 275; ++x) darkest = std::min(darkest, int(image.pixel(x, y)[0]));
    CHECK(darkest == Approx(128).margin(3));  // half blue over white, never a quarter
}

TEST_CASE("the legend box sits in the requested corner", "[plot]") {
    const Rect frame{60, 40, 280, 200};
    const float em = PlotStyle{}.label_size;
    for (Legend corner : {Legend::upper_left, Legend::upper_right, Legend::lower_left, Legend::lower_right}) {
        Axes axes;
        axes.x_range = std::pair{0.0, 1.0};
        axes.y_range = std::pair{0.0, 1.0};
        axes.legend = corner;
        Series a, b;
        a.label = "d=2", a.dash = dashed(1.5f);
        b.label = "filled", b.line_width = 0, b.marker_size = 6;
        axes.series = {a, b};  // no data: the legend is the only ink inside the frame
        const Image image = plot(axes, frame);
        int left = INT_MAX, right = INT_MIN, top = INT_MAX, bottom = INT_MIN;
        for (int y = 43; y < 237; ++y)
            for (int x = 63; x < 337; ++x)
                if (image.pixel(x, y)[1] < 250)
                    left = std::min(left, x), right = std::max(right, x), top = std::min(top, y),
                    bottom = std::max(bottom, y);
        INFO("corner " << int(corner));
        REQUIRE(left < right);
        const bool at_left = corner == Legend::upper_left || corner == Legend::lower_left;
        const bool at_top = corner == Legend::upper_left || corner == Legend::upper_right;
        // Half an em from the frame's edges, matplotlib's borderaxespad.
        if (at_left) CHECK(left - 60 == Approx(0.5 * em).margin(2));
        else CHECK(340 - (right + 1) == Approx(0.5 * em).margin(2));
        if (at_top) CHECK(top - 40 == Approx(0.5 * em).margin(2));
        else CHECK(240 - (bottom + 1) == Approx(0.5 * em).margin(2));
        CHECK(right - left < 140);  // a box around the entries, not the whole frame
        CHECK(bottom - top < 80);
    }
}

TEST_CASE("non-positive values on a log axis are skipped", "[plot]") {
    const Rect frame{50, 40, 300, 200};
    Axes axes;
    axes.x_scale = axes.y_scale = Scale::log;
    Series s = marker_at(0, 0);
    s.x = {-1, 0, 10, 100, 1000, 5, NAN};
    s.y = {5, 3, 0, 10, 100, -2, 7};
    axes.series = {s};
    Image image;
    REQUIRE_NOTHROW(image = plot(axes, frame));
    // Only (100, 10) and (1000, 100) are drawn, and the range fits them with 5% margins.
    const Blob ink = red_ink(image);
    CHECK(ink.left == Approx(50 + 300 * 0.05 / 1.1 - 4).margin(1.5));
    CHECK(ink.right + 1 == Approx(350 - 300 * 0.05 / 1.1 + 4).margin(1.5));
    const double radius = (8 + PlotStyle{}.marker_edge) / 2;
    CHECK(ink.count == Approx(2 * 3.14159 * radius * radius).margin(25));  // two markers, their solid red cores
    // Nothing positive at all: an empty axes, not an exception.
    Axes empty;
    empty.x_scale = Scale::log;
    empty.series = {marker_at(-1, 1)};
    CHECK_NOTHROW(plot(empty, frame));
    Axes bad;
    bad.y_scale = Scale::log;
    bad.y_range = std::pair{0.0, 10.0};
    CHECK_THROWS_AS(plot(bad, frame), std::invalid_argument);
}

TEST_CASE("plot row frames follow matplotlib's subplot margins", "[plot]") {
    const std::vector<Rect> frames = plot_row(900, 450, 3, PlotStyle{});
    REQUIRE(frames.size() == 3);
    // matplotlib: left 112.5, top 54, each 205.1 wide and 346.5 high, 41 apart.
    CHECK(frames[0].x == Approx(112.5).margin(1));
    CHECK(frames[0].y == Approx(54).margin(1));
    CHECK(frames[0].w == Approx(205.1).margin(1));
    CHECK(frames[0].h == Approx(346.5).margin(1));
    CHECK(frames[1].x - frames[0].right() == Approx(41).margin(1));
    CHECK(frames[2].right() == Approx(810).margin(1.5));
    // A page too small for matplotlib's fractions still leaves room for the labels.
    const Rect small = plot_row(200, 150, 1, PlotStyle{})[0];
    CHECK(small.x >= 60);
    CHECK(150 - small.bottom() >= 40);
}

TEST_CASE("a polyline joins its segments without gaps", "[plot]") {
    Canvas canvas(120, 120);
    canvas.clear({1, 1, 1, 1});
    Shapes shapes;
    const std::vector<glm::vec2> corner{{20, 100}, {60, 20}, {100, 100}};  // a sharp turn at the top
    shapes.polyline(corner, 8, red);
    shapes.draw(canvas);
    const Image image = canvas.read();
    // The outer corner is filled round: solid red just above the vertex, where separate quads leave a notch.
    CHECK(is_red(image, 60, 18));
    CHECK(is_red(image, 60, 22));
}

namespace {

// A log-log plot like tc7-7's, with a title, both axis labels, a note and a legend.
Axes labelled_axes() {
    Axes axes;
    axes.x_scale = axes.y_scale = Scale::log;
    axes.x_range = std::pair{1.0, 1000.0};
    axes.y_range = std::pair{1.0, 1e5};
    axes.x_label = "Time Steps";
    axes.y_label = "Number of Cells";
    axes.title = "rule 20";
    axes.legend = Legend::upper_left;
    Series s;
    s.label = "d=2";
    axes.series = {s};
    axes.notes = {{"slope 1.97", {0.55f, 0.1f}}};
    return axes;
}

bool covers(const Rect& r, int x, int y, float margin) {
    return x + 1 > r.x - margin && x < r.right() + margin && y + 1 > r.y - margin && y < r.bottom() + margin;
}

}  // namespace

TEST_CASE("the text a plot's fit check reads is where the plot draws its text", "[plot][layout]") {
    const Rect frame{90, 40, 420, 200};
    const Axes axes = labelled_axes();
    PageText page;
    axes_text(page, frame, axes, PlotStyle{}, 0);
    REQUIRE(page.panels.size() == 1);
    CHECK(page.panels[0].what == "the frame of the plot");
    // Every text by name: 4 x ticks (1 to 1000), 6 y ticks (1 to 1e5), two axis labels, the title, the note, the legend.
    std::vector<std::string> names;
    for (const PageText::Box& t : page.texts) names.push_back(t.what);
    for (const char* name : {"the x tick label \"10⁰\"", "the x tick label \"10³\"", "the y tick label \"10⁵\"",
                             "the x axis label", "the y axis label", "the title", "the note \"slope 1.97\"",
                             "the legend"})
        CHECK(std::count(names.begin(), names.end(), name) == 1);
    CHECK(names.size() == 4 + 6 + 2 + 1 + 1 + 1);
    CHECK(text_clash(page, {0, 0, 560, 300}).empty());

    // Every pixel of ink outside the frame and its ticks lies in a text's box, and every text's box holds ink.
    const Image image = plot(axes, frame, 560, 300);
    const float tick = PlotStyle{}.major_tick + 2;
    const Rect ticked{frame.x - tick, frame.y - 2, frame.w + tick + 2, frame.h + tick + 2};
    int stray = 0;
    std::vector<int> ink_in(page.texts.size(), 0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            if (image.pixel(x, y)[0] > 200) continue;  // white or nearly
            bool in_text = false;
            for (std::size_t i = 0; i < page.texts.size(); ++i)
                if (covers(page.texts[i].box, x, y, 1.0f)) in_text = true, ++ink_in[i];
            if (!in_text && !covers(ticked, x, y, 0)) ++stray;
        }
    CHECK(stray == 0);
    for (std::size_t i = 0; i < page.texts.size(); ++i) {
        INFO(page.texts[i].what);
        CHECK(ink_in[i] > 0);
    }
}

TEST_CASE("a plot too small for its text clashes and the size that fits holds it", "[plot][layout]") {
    const std::vector<Axes> row(3, labelled_axes());
    auto row_text = [&](int w, int h) {
        PageText page;
        const auto frames = plot_row(w, h, 3, PlotStyle{});
        for (int i = 0; i < 3; ++i) axes_text(page, frames[i], row[i], PlotStyle{}, i + 1);
        return page;
    };
    const std::string clash = text_clash(row_text(333, 111), {0, 0, 333, 111});
    CHECK_FALSE(clash.empty());
    CHECK(clash.find(" of plot ") != std::string::npos);
    const PageSize fits = size_that_fits(333, 111, row_text);
    REQUIRE(fits.width > 333);
    CHECK(fits.height * 333 == Approx(fits.width * 111).margin(333));
    const PageText roomy = row_text(fits.width, fits.height);
    CHECK(text_clash(roomy, {0, 0, float(fits.width), float(fits.height)}).empty());
    // The last size short of it still clashes: the size named is the first that fits.
    const int w = int(std::ceil(fits.width / 1.05)) - 1, h = int(std::ceil(fits.height / 1.05)) - 1;
    CHECK_FALSE(text_clash(row_text(w, h), {0, 0, float(w), float(h)}).empty());
}

TEST_CASE("a colour bar's text is checked beside its field", "[plot][layout]") {
    ColourBar bar;
    bar.colormap = *find_colormap("viridis");
    bar.low = 0, bar.high = 2000;
    bar.label = "arrival time (monolayers)";
    PageText page;
    colour_bar_text(page, {20, 30, 200, 400}, bar, PlotStyle{}, 1);
    REQUIRE(page.panels.size() == 1);
    CHECK(page.panels[0].what == "the colour bar of panel 1");
    CHECK(page.texts.back().what == "the colour bar's label of panel 1");
    CHECK(text_clash(page, {0, 0, 500, 460}).empty());
    // The page cut just right of the bar: its labels run off it.
    const std::string clash = text_clash(page, {0, 0, page.panels[0].box.right() + 8, 460});
    CHECK(clash.find("the colour bar's") == 0);
    CHECK(clash.find("runs off the page") != std::string::npos);
}
