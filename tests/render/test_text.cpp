#include <catch2/catch.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <vector>
#include <string>

#include "render/gl/canvas.hpp"
#include "render/text.hpp"
#include "base/utf8.hpp"

using render::Align;
using render::Baseline;
using render::Canvas;
using render::Font;
using render::Image;
using render::Text;

namespace {

const glm::vec4 black{0, 0, 0, 1};
const glm::vec4 white{1, 1, 1, 1};

// The bounding box of the pixels darker than the white background by more
// than `threshold` (0..255), with their count: the ink a string left.
struct Ink {
    int left = INT_MAX, top = INT_MAX, right = INT_MIN, bottom = INT_MIN;  // inclusive pixel indices
    int count = 0;
    bool empty() const { return count == 0; }
    int width() const { return right - left + 1; }
    int height() const { return bottom - top + 1; }
    float centre_x() const { return (left + right + 1) / 2.0f; }  // pixel edges, not indices
    float centre_y() const { return (top + bottom + 1) / 2.0f; }
};

Ink ink(const Image& image, int threshold = 32) {
    Ink box;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const auto* p = image.pixel(x, y);
            const int darkness = 255 - std::min({int(p[0]), int(p[1]), int(p[2])});
            if (darkness <= threshold) continue;
            box.left = std::min(box.left, x), box.right = std::max(box.right, x);
            box.top = std::min(box.top, y), box.bottom = std::max(box.bottom, y);
            ++box.count;
        }
    return box;
}

// Draws one string in black on a white canvas and returns what it left.
Image render_one(Font& font, const std::string& s, glm::vec2 at, Align align = Align::left,
                 Baseline baseline = Baseline::baseline, float rotation = 0, int w = 200, int h = 120) {
    Canvas canvas(w, h);
    canvas.clear(white);
    Text text;
    text.add(font, s, at, black, align, baseline, rotation);
    text.draw(canvas);
    return canvas.read();
}

}  // namespace

TEST_CASE("UTF-8 decoding gives the code points of tick labels, Greek and Latin-1", "[text]") {
    CHECK(base::decode_utf8("10⁻³ α×β") == std::u32string{U'1', U'0', 0x207B, 0x00B3, U' ', 0x03B1, 0x00D7, 0x03B2});
    CHECK(base::decode_utf8("−2 °C, µ²") ==
          std::u32string{0x2212, U'2', U' ', 0x00B0, U'C', U',', U' ', 0x00B5, 0x00B2});
    CHECK(base::decode_utf8("λμπστφγδ") == U"λμπστφγδ");
    CHECK(base::decode_utf8("Ångström, naïve") == U"Ångström, naïve");
    CHECK(base::decode_utf8("⁰¹²³⁴⁵⁶⁷⁸⁹") ==
          std::u32string{0x2070, 0xB9, 0xB2, 0xB3, 0x2074, 0x2075, 0x2076, 0x2077, 0x2078, 0x2079});
    CHECK(base::decode_utf8("\xF0\x9F\x98\x80") == std::u32string{0x1F600});  // four bytes
    CHECK(base::decode_utf8("").empty());
}

TEST_CASE("malformed UTF-8 becomes U+FFFD and decoding resumes", "[text]") {
    const char32_t bad = base::replacement_character;
    CHECK(base::decode_utf8("a\x80z") == std::u32string{U'a', bad, U'z'});      // stray continuation
    CHECK(base::decode_utf8("a\xE2\x81z") == std::u32string{U'a', bad, U'z'});  // truncated by a new character
    CHECK(base::decode_utf8("a\xE2\x81") == std::u32string{U'a', bad});         // truncated by the end
    CHECK(base::decode_utf8("\xC0\xAF") == std::u32string{bad});                // overlong '/'
    CHECK(base::decode_utf8("\xED\xA0\x80") == std::u32string{bad});            // a surrogate
    CHECK(base::decode_utf8("\xF4\x90\x80\x80") == std::u32string{bad});        // above U+10FFFF
    CHECK(base::decode_utf8("\xFF!") == std::u32string{bad, U'!'});
}

TEST_CASE("a font that cannot be loaded throws naming its path", "[text]") {
    const std::string path = "/nonexistent/fonts/NoSuchFont.ttf";
    CHECK_THROWS_WITH(Font(12, path), Catch::Contains(path));
    CHECK_THROWS_AS(Font(0), std::invalid_argument);
    CHECK_THROWS_AS(Font(-3), std::invalid_argument);
}

TEST_CASE("DejaVu Sans metrics scale with the pixel size", "[text]") {
    const Font font(20);
    CHECK(font.pixel_size() == 20);
    CHECK(font.path() == FIGGEN_FONT_PATH);
    // DejaVu Sans: 2048 units per em, ascender 1901, descender -483, line gap 0, capitals 1493.
    CHECK(font.ascender() == Approx(20 * 1901 / 2048.0).epsilon(1e-4));
    CHECK(font.descender() == Approx(20 * -483 / 2048.0).epsilon(1e-4));
    CHECK(font.line_height() == Approx(font.ascender() - font.descender()).epsilon(1e-4));
    CHECK(font.cap_height() == Approx(20 * 1493 / 2048.0).epsilon(1e-3));
}

TEST_CASE("advance widths: narrow and wide letters, kerning, linear in size", "[text]") {
    Font font(20);
    CHECK(font.width("") == 0);
    CHECK(font.width("ii") < font.width("MM"));
    CHECK(font.width("ii") == Approx(2 * font.width("i")));  // no kerning between these
    CHECK(font.width("Hello") > 3 * 20 * 0.5);                // five letters of about half an em or more
    CHECK(font.width("Hello") < 5 * 20);
    // DejaVu Sans kerns A against V: the pair is tighter than its letters.
    CHECK(font.width("AV") < font.width("A") + font.width("V") - 0.5f);
    // Unhinted advances: the same string at another size scales in proportion.
    Font big(47);
    for (const char* s : {"Hello", "step 15", "10⁻³ α×β", "AVAVAV"})
        CHECK(big.width(s) == Approx(font.width(s) * 47 / 20).epsilon(0.02));
    // Non-ASCII characters have real advances, and an unknown one draws the .notdef box, not nothing.
    CHECK(font.width("α") > 5);
    CHECK(font.width("\xEE\x80\x80") > 5);  // U+E000, private use: not in the font
}

TEST_CASE("a black string on white leaves ink only inside its line box", "[text]") {
    Font font(24);
    const glm::vec2 at{20.3f, 60};
    const Image image = render_one(font, "step 15", at);
    const Ink box = ink(image, 8);  // even faint anti-aliasing counts here
    REQUIRE(!box.empty());
    const float w = font.width("step 15");
    CHECK(box.left >= at.x - 2);
    CHECK(box.right + 1 <= at.x + w + 2);
    CHECK(box.top >= at.y - font.ascender() - 2);
    CHECK(box.bottom + 1 <= at.y - font.descender() + 2);
    // "p" descends below the baseline, "t" and "1" rise near the capitals.
    CHECK(box.bottom + 1 > at.y + 2);
    CHECK(box.top < at.y - font.cap_height() + 2);
    CHECK(box.width() > w - 4);
    // Strokes about 2.5 px thick: the ink is a fraction of the box, neither a smudge nor a fill.
    const Ink dark = ink(image, 128);
    const float area = w * font.line_height();
    CHECK(dark.count > 0.08 * area);
    CHECK(dark.count < 0.40 * area);
    // Solid black where strokes are: the coverage reaches full strength.
    int darkest = 255;
    for (int y = box.top; y <= box.bottom; ++y)
        for (int x = box.left; x <= box.right; ++x) darkest = std::min(darkest, int(image.pixel(x, y)[1]));
    CHECK(darkest < 20);
    CHECK(int(image.pixel(box.left, box.top)[3]) == 255);  // alpha stays opaque over the background
}

TEST_CASE("alignment anchors the line at its left, centre or right", "[text]") {
    Font font(24);
    const glm::vec2 at{100.4f, 60};
    const float w = font.width("step 15");
    const Ink centred = ink(render_one(font, "step 15", at, Align::centre));
    CHECK(std::abs(centred.centre_x() - at.x) <= 1.5);
    const Ink right = ink(render_one(font, "step 15", at, Align::right));
    CHECK(right.right + 1 <= at.x + 1);
    CHECK(right.right + 1 >= at.x - 3);
    CHECK(right.left >= at.x - w - 1);
    const Ink left = ink(render_one(font, "step 15", at, Align::left));
    CHECK(left.left >= at.x - 1);
    CHECK(left.left <= at.x + 3);
    // The three are the same ink moved sideways.
    CHECK(std::abs(left.count - centred.count) < left.count / 20);
    CHECK(std::abs(left.count - right.count) < left.count / 20);
}

TEST_CASE("vertical anchors: top and bottom of the line box, middle of the capitals", "[text]") {
    Font font(30);
    const glm::vec2 at{20, 60};
    const Ink top = ink(render_one(font, "HÉg", at, Align::left, Baseline::top));
    CHECK(top.top >= at.y - 1);  // the accent stays under the line box's top
    CHECK(top.bottom + 1 <= at.y + font.line_height() + 1);
    const Ink bottom = ink(render_one(font, "HÉg", at, Align::left, Baseline::bottom));
    CHECK(bottom.bottom + 1 <= at.y + 1);
    CHECK(bottom.bottom + 1 >= at.y + font.descender() * 0.3f);  // "g" reaches well into the descender
    const Ink middle = ink(render_one(font, "HIH", at, Align::left, Baseline::middle));
    CHECK(std::abs(middle.centre_y() - at.y) <= 1);
    const Ink on_baseline = ink(render_one(font, "HIH", at));
    CHECK(on_baseline.bottom + 1 == Approx(at.y).margin(1));
    CHECK(on_baseline.height() == Approx(font.cap_height()).margin(1.5));
}

TEST_CASE("a line turned 90 degrees reads bottom to top beside its anchor", "[text]") {
    Font font(24);
    const glm::vec2 at{60, 180};
    const float w = font.width("step 15");
    const Ink box = ink(render_one(font, "step 15", at, Align::left, Baseline::baseline, 90, 120, 200));
    REQUIRE(!box.empty());
    CHECK(box.height() > 2 * box.width());
    CHECK(box.height() > w - 4);
    // Counter-clockwise: the text runs up from the anchor, its letters' tops point left.
    CHECK(box.bottom + 1 <= at.y + 2);
    CHECK(box.top >= at.y - w - 2);
    CHECK(box.left >= at.x - font.ascender() - 2);
    CHECK(box.right + 1 <= at.x - font.descender() + 2);
    CHECK(box.right + 1 > at.x + 2);  // only "p" reaches past the baseline, to the right
    // Same ink as the upright line, give or take the filtering at other offsets.
    const Ink upright = ink(render_one(font, "step 15", {20, 60}));
    CHECK(std::abs(box.count - upright.count) < upright.count / 10);
    // A centred y-axis label centres along the axis.
    const Ink centred = ink(render_one(font, "step 15", {60, 100}, Align::centre, Baseline::bottom, 90, 120, 200));
    CHECK(std::abs(centred.centre_y() - 100) <= 1.5);
    CHECK(centred.right + 1 <= 60 + 1);
}

TEST_CASE("superscripts and symbols are real glyphs, not .notdef boxes", "[text]") {
    Font font(40);
    const glm::vec2 at{20, 80};
    // Superscript minus and three float above the baseline.
    const Ink sup = ink(render_one(font, "⁻³", at));
    REQUIRE(!sup.empty());
    CHECK(sup.bottom + 1 < at.y - 0.25f * font.cap_height());
    // A .notdef box sits on the baseline; the degree sign does not.
    const Ink degree = ink(render_one(font, "°", at));
    CHECK(degree.bottom + 1 < at.y - 0.4f * font.cap_height());
    const Ink unknown = ink(render_one(font, "\xEE\x80\x80", at));
    REQUIRE(!unknown.empty());
    CHECK(unknown.bottom + 1 >= at.y);  // DejaVu's box reaches into the descender
    // Greek letters have ink of their own.
    const Ink greek = ink(render_one(font, "αβγδλμπστφ", {4, 80}, Align::left, Baseline::baseline, 0, 400, 120));
    CHECK(greek.width() > 8 * font.pixel_size() * 0.4);
}

TEST_CASE("colour and alpha reach the pixels", "[text]") {
    Font font(32);
    Canvas canvas(120, 60);
    canvas.clear(white);
    Text text;
    text.add(font, "IIII", {10, 45}, {1, 0, 0, 1});
    text.add(font, "IIII", {70, 45}, {0, 0, 1, 0.5f});
    text.draw(canvas);
    const Image image = canvas.read();
    int reddest = 0, blue_min_red = 255;
    for (int y = 0; y < 60; ++y) {
        for (int x = 0; x < 60; ++x) {
            const auto* p = image.pixel(x, y);
            CHECK(int(p[0]) == 255);  // red over white keeps full red
            reddest = std::max(reddest, 255 - int(p[1]));
        }
        for (int x = 60; x < 120; ++x) blue_min_red = std::min(blue_min_red, int(image.pixel(x, y)[0]));
    }
    CHECK(reddest > 240);
    // Half-transparent blue over white: the strongest pixel is half way.
    CHECK(blue_min_red == Approx(128).margin(8));
}

TEST_CASE("one batch holds several fonts and the atlas grows without losing glyphs", "[text]") {
    Font small(16), big(150);
    Canvas canvas(300, 200);
    canvas.clear(white);
    Text text;
    text.add(big, "A", {20, 170}, black);
    text.add(small, "A", {200, 40}, black);
    text.draw(canvas);
    const Image before = canvas.read();
    const Ink big_a = ink(before);
    REQUIRE(!big_a.empty());
    CHECK(big_a.height() > 100);  // the big "A" ...
    CHECK(big_a.left < 100);
    int small_ink = 0;            // ... and the small one, elsewhere
    for (int y = 20; y < 45; ++y)
        for (int x = 195; x < 220; ++x) small_ink += before.pixel(x, y)[1] < 128 ? 1 : 0;
    CHECK(small_ink > 10);

    // Many glyphs at 150 px overflow the starting atlas, which must grow and
    // still hold the "A" placed first.
    std::string alphabet;
    for (char c = 'B'; c <= 'Z'; ++c) alphabet += c;
    for (char c = 'a'; c <= 'z'; ++c) alphabet += c;
    Text more;
    more.add(big, alphabet, {0, 170}, black);  // rasterises them all
    canvas.clear(white);
    text.draw(canvas);
    const Image after = canvas.read();
    CHECK(after.rgba == before.rgba);
}

namespace {

// Collects the missing-glyph warnings while it lives.
struct Warnings {
    std::vector<std::string> lines;
    Warnings() {
        render::set_missing_glyph_warning([this](const std::string& line) { lines.push_back(line); });
    }
    ~Warnings() {
        render::set_missing_glyph_warning([](const std::string& line) {
            std::fprintf(stderr, "figgen: warning: %s\n", line.c_str());
        });
    }
};

std::set<std::string> face_files(const Font& font, const Font::Shaped& shaped) {
    std::set<std::string> files;
    for (const Font::ShapedGlyph& g : shaped.glyphs)
        files.insert(font.face_file(g.face).path + "#" + std::to_string(font.face_file(g.face).index));
    return files;
}

}  // namespace

TEST_CASE("a Chinese caption is drawn from Noto Sans CJK with real glyphs and no warning", "[text]") {
    Warnings warnings;
    Font font(32);
    // Liu and Zhang's caption of their Fig 3, with a Latin digit and CJK quotation marks.
    const std::string caption = "图3 “奇偶规则”生长出的雪花瞬时图象";
    const Font::Shaped shaped = font.shape(caption, "zh-cn");
    REQUIRE(shaped.glyphs.size() == base::decode_utf8(caption).size());
    for (const Font::ShapedGlyph& g : shaped.glyphs) CHECK(g.index != 0);  // no .notdef
    // The ideographs come from the Simplified Chinese face of the collection
    // (index 2 of NotoSansCJK-Regular.ttc), the digit and space from DejaVu Sans.
    const auto files = face_files(font, shaped);
    CHECK(files.count(std::string(FIGGEN_FONT_PATH) + "#0") == 1);
    CHECK(files.count("/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc#2") == 1);
    // Ideographs are one em wide: 雪花 is two.
    CHECK(font.width("雪花", "zh-cn") == Approx(64).margin(0.05));
    // In Japanese the same characters take the Japanese face (index 0).
    CHECK(face_files(font, font.shape("弾道軌道凝集", "ja")).count("/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc#0") ==
          1);
    // And they leave ink: each ideograph marks its em square.
    const Image image = [&] {
        Canvas canvas(600, 60);
        canvas.clear(white);
        Text text;
        text.add(font, caption, {4, 44}, black, Align::left, Baseline::baseline, 0, "zh-cn");
        text.draw(canvas);
        return canvas.read();
    }();
    const Ink box = ink(image);
    CHECK(box.width() > 16 * 32 * 0.85);
    CHECK(warnings.lines.empty());
}

TEST_CASE("a character no installed font has is a box with a warning naming it", "[text]") {
    Warnings warnings;
    Font font(24);
    const Font::Shaped shaped = font.shape("a\U0010FFFDb");  // plane 16's private use
    REQUIRE(shaped.glyphs.size() == 3);
    CHECK(shaped.glyphs[1].index == 0);
    REQUIRE(warnings.lines.size() == 1);
    CHECK(warnings.lines[0].find("U+10FFFD") != std::string::npos);
    font.shape("\U0010FFFD again");
    CHECK(warnings.lines.size() == 1);  // once a process
}

TEST_CASE("lines are shaped: kerning and marks and right to left", "[text]") {
    Font font(40);
    // GPOS kerning pulls A and V together.
    CHECK(font.width("AV") < font.width("A") + font.width("V") - 1);
    // e and a combining acute become the precomposed é.
    const Font::Shaped combined = font.shape("e\u0301");
    REQUIRE(combined.glyphs.size() == 1);
    CHECK(combined.glyphs[0].index == font.shape("\u00e9").glyphs[0].index);
    // A combining mark with no precomposed form sits on its base, not after it.
    const Font::Shaped marked = font.shape("x\u0323");  // x with dot below
    REQUIRE(marked.glyphs.size() == 2);
    CHECK(marked.glyphs[1].position.x < font.width("x"));
    // Hebrew runs right to left: the first character is drawn rightmost.
    const Font::Shaped hebrew = font.shape("שלום");
    REQUIRE(hebrew.glyphs.size() == 4);
    CHECK(hebrew.glyphs.front().cluster > hebrew.glyphs.back().cluster);
    CHECK(hebrew.glyphs.back().cluster == 0);
    // In a Latin line a Hebrew word keeps its own direction inside it.
    const Font::Shaped mixed = font.shape("ab שלום cd");
    REQUIRE(mixed.glyphs.size() == 10);
    CHECK(mixed.glyphs[0].cluster == 0);
    CHECK(mixed.glyphs[3].cluster > mixed.glyphs[6].cluster);
    // Arabic letters join: beh between two behs is not the isolated beh.
    const unsigned isolated = font.shape("\u0628").glyphs[0].index;
    const Font::Shaped joined = font.shape("\u0628\u0628\u0628");
    REQUIRE(joined.glyphs.size() == 3);
    CHECK(joined.glyphs[1].index != isolated);
}

TEST_CASE("wrap breaks Latin between words and Chinese between characters", "[text]") {
    Font font(20);
    const auto latin = render::wrap(font, "the quick brown fox jumps over the lazy dog", 120);
    REQUIRE(latin.size() > 2);
    std::string joined;
    for (const std::string& line : latin) {
        CHECK(font.width(line) <= 120);
        CHECK(line.front() != ' ');
        CHECK(line.back() != ' ');
        joined += (joined.empty() ? "" : " ") + line;
    }
    CHECK(joined == "the quick brown fox jumps over the lazy dog");
    // Ideographs break anywhere but never before a closing mark: 100 px holds five.
    const auto chinese = render::wrap(font, "雪花是自然界的生长现象，它具有复杂的树枝状形态。", 100, "zh-cn");
    REQUIRE(chinese.size() >= 5);
    std::string all;
    for (const std::string& line : chinese) {
        CHECK(font.width(line, "zh-cn") <= 100);
        CHECK(line.rfind("，", 0) != 0);
        CHECK(line.rfind("。", 0) != 0);
        all += line;
    }
    CHECK(all == "雪花是自然界的生长现象，它具有复杂的树枝状形态。");
    // A word wider than the room stays whole on its own line.
    const auto long_word = render::wrap(font, "a supercalifragilistic b", 60);
    CHECK(long_word == std::vector<std::string>{"a", "supercalifragilistic", "b"});
}

TEST_CASE("a line's ink boxes hold the pixels it draws upright and turned", "[text][layout]") {
    for (const float rotation : {0.0f, 90.0f}) {
        INFO("rotation " << rotation);
        Font font(24);
        const glm::vec2 at{60.3f, 100};
        const render::LineInk line = render::line_ink(font, "Hyp 15, g", at, Align::centre, Baseline::middle, rotation);
        REQUIRE(line.glyphs.size() == 7);  // the two spaces have no ink
        const Image image = render_one(font, "Hyp 15, g", at, Align::centre, Baseline::middle, rotation, 200, 200);
        const Ink drawn = ink(image, 96);  // the solid ink; its faint anti-aliased rim may spill a pixel
        REQUIRE(!drawn.empty());
        CHECK(drawn.left >= line.box.x - 1);
        CHECK(drawn.right + 1 <= line.box.right() + 1);
        CHECK(drawn.top >= line.box.y - 1);
        CHECK(drawn.bottom + 1 <= line.box.bottom() + 1);
        // Tight: the box is the ink's, within a pixel, not the line box with its accent room.
        CHECK(line.box.x > drawn.left - 2);
        CHECK(line.box.right() < drawn.right + 1 + 2);
        CHECK(line.box.y > drawn.top - 2);
        CHECK(line.box.bottom() < drawn.bottom + 1 + 2);
        const float across = rotation == 0 ? line.box.h : line.box.w;
        CHECK(across < font.ascender() - font.descender() - 4);
        // Every dark pixel lies in one of the glyphs' boxes.
        int outside = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                if (image.pixel(x, y)[0] > 96) continue;
                bool in = false;
                for (const render::Rect& g : line.glyphs)
                    in = in || (x + 1 > g.x - 1 && x < g.right() + 1 && y + 1 > g.y - 1 && y < g.bottom() + 1);
                outside += in ? 0 : 1;
            }
        CHECK(outside == 0);
    }
    Font font(24);
    CHECK(render::line_ink(font, "   ", {10, 10}).box.w == 0);
    CHECK(render::line_ink(font, "", {10, 10}).glyphs.empty());
}
