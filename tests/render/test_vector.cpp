// The vector backend: what a VectorPage records of a drawing, and the PDF
// and SVG the vector module writes of it, read back with poppler and
// librsvg.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <variant>

#include "figgen_run.hpp"
#include "base/atomic_file.hpp"
#include "render/gl/canvas.hpp"
#include "render/colormap.hpp"
#include "render/field.hpp"
#include "render/hex_cells.hpp"
#include "render/plot.hpp"
#include "render/shapes.hpp"
#include "render/text.hpp"
#include "render/vector/vector.hpp"
#include "render/vector/vector_page.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/helpers/field_spec.hpp"
#include "sim/grid.hpp"
#include "vector_check.hpp"

namespace fs = std::filesystem;

namespace {

template <typename T>
int count(const render::VectorPage& page) {
    int n = 0;
    for (const auto& item : page.page().items) n += std::holds_alternative<T>(item);
    return n;
}

int moves(const render::vector::Path& path) {
    int n = 0;
    for (const auto& step : path) n += step.kind == render::vector::PathStep::move;
    return n;
}

// Writes `page` as `format` into `dir`; returns its path.
fs::path write(const render::VectorPage& page, const fs::path& dir, const std::string& name,
               render::vector::Format format, std::uint64_t max_bytes = 1u << 30) {
    base::AtomicFile file(dir / name);
    render::vector::write(file.fd(), file.final_path(), format, page.page(), max_bytes);
    file.commit();
    return dir / name;
}

}  // namespace

TEST_CASE("a vector page joins a plant's round segments into one stroke and opaque runs into one path", "[vector]") {
    render::VectorPage page(200, 100, false);
    page.background({1, 1, 1, 1});
    render::Shapes shapes;
    const glm::vec4 green{0, 0.5f, 0, 1}, red{1, 0, 0, 1};
    // A branch of three segments end to end, and a second one apart.
    shapes.round_segment({10, 90}, {10, 60}, 3, green);
    shapes.round_segment({10, 60}, {20, 40}, 2.9f, green);  // another width: a stroke of its own
    shapes.round_segment({20, 40}, {25, 20}, 2.9f, green);
    shapes.round_segment({50, 90}, {50, 60}, 2.9f, green);  // starts elsewhere: a new subpath
    shapes.disc({100, 50}, 5, red);
    shapes.rect({120, 40, 10, 10}, red);
    shapes.triangle({140, 40}, {150, 40}, {145, 30}, red);
    shapes.draw(page);
    const auto& items = page.page().items;
    REQUIRE(items.size() == 4);  // the background, two strokes, one fill
    const auto& first = std::get<render::vector::Stroke>(items[1]);
    CHECK(first.cap == render::vector::Cap::round);
    CHECK(moves(first.path) == 1);
    CHECK(first.path.size() == 2);
    const auto& second = std::get<render::vector::Stroke>(items[2]);
    CHECK(second.width == 2.9f);
    CHECK(moves(second.path) == 2);  // the branch's two joined segments, and the one apart
    CHECK(second.path.size() == 5);
    const auto& fill = std::get<render::vector::Fill>(items[3]);
    CHECK(fill.colour == red);
    CHECK(fill.path.front().kind == render::vector::PathStep::circle);
    CHECK(moves(fill.path) == 2);  // the square and the triangle; the disc is a circle
}

TEST_CASE("a translucent line drawn once is painted opaque in a group laid over the page at its alpha",
          "[vector]") {
    render::VectorPage page(100, 100, false);
    render::Shapes line;
    const std::vector<glm::vec2> zigzag = {{10, 10}, {50, 90}, {90, 10}};
    line.polyline(zigzag, 4, {0, 0, 1, 0.5f}, render::dashed(4));
    page.shapes(line, render::Coverage::once);
    const auto& items = page.page().items;
    REQUIRE(items.size() == 3);
    CHECK(std::holds_alternative<render::vector::GroupBegin>(items[0]));
    const auto& stroke = std::get<render::vector::Stroke>(items[1]);
    CHECK(stroke.colour.a == 1.0f);
    CHECK(stroke.dash == std::vector<float>{3.7f * 4, 1.6f * 4});
    CHECK(std::get<render::vector::GroupEnd>(items[2]).alpha == 0.5f);
    // Drawn plainly (Coverage::each), each piece blends by itself: no group.
    render::VectorPage plain(100, 100, false);
    line.draw(plain);
    CHECK(count<render::vector::GroupBegin>(plain) == 0);
    CHECK(std::get<render::vector::Stroke>(plain.page().items[0]).colour.a == 0.5f);
}

TEST_CASE("text in a PDF is the font's own glyphs, embedded as TrueType, and reads back as the same words",
          "[vector]") {
    const fs::path dir = testkit::fresh_dir("vector-text");
    render::VectorPage page(400, 120, false);
    page.background({1, 1, 1, 1});
    render::Text text;
    render::Font& font = render::font_of_size(20);
    text.add(font, "Number of Cells \u2265 10\u00b2", {20, 40}, {0, 0, 0, 1});
    text.add(font, "azimuth 30\u00b0", {300, 110}, {0, 0, 0, 1}, render::Align::left, render::Baseline::baseline, 90);
    text.draw(page);
    REQUIRE(count<render::vector::Glyphs>(page) == 2);
    const auto& glyphs = std::get<render::vector::Glyphs>(page.page().items[1]);
    CHECK(glyphs.font_path == font.path());
    CHECK(glyphs.text == "Number of Cells \u2265 10\u00b2");
    CHECK(glyphs.glyphs.size() == 21);  // one a character
    CHECK(glyphs.glyphs[1].position.x > glyphs.glyphs[0].position.x);
    const fs::path pdf = write(page, dir, "text.pdf", render::vector::Format::pdf);
    // cairo subsets the font: its Latin-1 glyphs as a TrueType font, the others (≥) as a second.
    const auto fonts = testkit::pdf_fonts(pdf);
    REQUIRE_FALSE(fonts.empty());
    for (const auto& f : fonts) {
        INFO(f.name << ": " << f.type);
        CHECK(f.name.find("DejaVuSans") != std::string::npos);
        CHECK(f.type.find("TrueType") != std::string::npos);
        CHECK(f.embedded);
    }
    const testkit::ToolRun words = testkit::run_tool("pdftotext -layout '" + pdf.string() + "' -");
    REQUIRE(words.status == 0);
    CHECK(words.output.find("Number of Cells \u2265 10\u00b2") != std::string::npos);
    CHECK(words.output.find("azimuth") != std::string::npos);  // turned a quarter: poppler reads it in pieces
}

TEST_CASE("Chinese and Hebrew text in a PDF: fallback faces embedded and the words read back in order",
          "[vector]") {
    const fs::path dir = testkit::fresh_dir("vector-scripts");
    render::VectorPage page(500, 120, false);
    page.background({1, 1, 1, 1});
    render::Text text;
    render::Font& font = render::font_of_size(20);
    text.add(font, "图3 “奇偶规则”生长出的雪花瞬时图象", {20, 40}, {0, 0, 0, 1}, render::Align::left,
             render::Baseline::baseline, 0, "zh-cn");
    text.add(font, "שלום", {20, 90}, {0, 0, 0, 1});
    text.draw(page);
    // The caption's runs: DejaVu for "3 ", Noto Sans CJK SC for the rest.
    std::set<std::string> faces;
    for (const auto& item : page.page().items)
        if (const auto* g = std::get_if<render::vector::Glyphs>(&item))
            faces.insert(fs::path(g->font_path).filename().string() + "#" + std::to_string(g->font_index));
    CHECK(faces == std::set<std::string>{"DejaVuSans.ttf#0", "NotoSansCJK-Regular.ttc#2"});
    const fs::path pdf = write(page, dir, "scripts.pdf", render::vector::Format::pdf);
    bool cjk = false;
    for (const auto& f : testkit::pdf_fonts(pdf)) {
        INFO(f.name << ": " << f.type);
        CHECK(f.embedded);
        CHECK(f.type.find("Type 3") == std::string::npos);
        cjk = cjk || f.name.find("NotoSansCJKsc") != std::string::npos;
    }
    CHECK(cjk);
    const testkit::ToolRun words = testkit::run_tool("pdftotext '" + pdf.string() + "' -");
    REQUIRE(words.status == 0);
    CHECK(words.output.find("图3 “奇偶规则”生长出的雪花瞬时图象") != std::string::npos);
    CHECK(words.output.find("שלום") != std::string::npos);
}

TEST_CASE("a nearest field is embedded at its cells and marked so; a smooth one as the PNG resamples it",
          "[vector]") {
    const fs::path dir = testkit::fresh_dir("vector-field");
    const render::Colormap& reds = render::colormap("Reds");
    const std::vector<double> checker = {0, 1, 1, 0, 0, 1};  // 2 rows x 3 columns
    render::FieldStyle nearest{&reds, 0, 1, 1, render::Sampling::nearest};
    render::FieldStyle smooth = nearest;
    smooth.sampling = render::Sampling::smooth;
    render::VectorPage page(300, 100, false);
    render::draw_field(page, {0, 0, 150, 100}, 2, 3, checker, nearest);
    render::draw_field(page, {150, 0, 150, 100}, 2, 3, checker, smooth);
    const auto& cells = std::get<render::vector::Picture>(page.page().items[0]);
    CHECK(cells.image.width == 3);
    CHECK(cells.image.height == 2);
    CHECK_FALSE(cells.smooth);
    const glm::vec3 last = reds.at(1.0);  // the cell of value 1 at row 0, column 1
    CHECK(int(cells.image.pixel(1, 0)[0]) == int(std::lround(last.r * 255)));
    const auto& resampled = std::get<render::vector::Picture>(page.page().items[1]);
    CHECK(resampled.image.width == 150);
    CHECK(resampled.smooth);

    const std::string pdf = testkit::slurp(write(page, dir, "field.pdf", render::vector::Format::pdf));
    CHECK(pdf.find("/Interpolate false") != std::string::npos);
    CHECK(pdf.find("/Interpolate true") != std::string::npos);
    const std::string svg = testkit::slurp(write(page, dir, "field.svg", render::vector::Format::svg));
    // Marked for browsers, and enlarged by whole pixels for viewers that
    // ignore the mark (librsvg): 50 x 50 pixels a cell.
    CHECK(svg.find("<image style=\"image-rendering:optimizeSpeed;image-rendering:pixelated\" id=\"image") !=
          std::string::npos);
    CHECK(svg.find("width=\"150\" height=\"100\"") != std::string::npos);
    const render::Image raster = testkit::rasterise_svg(dir / "field.svg");
    // Cells are 50 pixels wide: flat inside, sharp at their edges.
    CHECK(int(raster.pixel(2, 2)[1]) == int(raster.pixel(48, 48)[1]));
    CHECK(int(raster.pixel(48, 10)[1]) == int(raster.pixel(2, 10)[1]));
    CHECK(int(raster.pixel(52, 10)[1]) == int(raster.pixel(98, 10)[1]));
    CHECK(int(raster.pixel(48, 10)[1]) != int(raster.pixel(52, 10)[1]));
}

TEST_CASE("a vector file that would pass its allowance stops with an error and leaves no file", "[vector]") {
    const fs::path dir = testkit::fresh_dir("vector-too-large");
    render::VectorPage page(100, 100, false);
    page.background({1, 1, 1, 1});
    for (auto format : {render::vector::Format::pdf, render::vector::Format::svg}) {
        try {
            write(page, dir, "big", format, 100);
            FAIL("a 100-byte allowance was not refused");
        } catch (const std::runtime_error& e) {
            CHECK(std::string(e.what()).find("more than the 100 bytes allowed") != std::string::npos);
        }
        CHECK(fs::is_empty(dir));
    }
}

TEST_CASE("a transparent canvas reads back straight colour over alpha 0", "[vector][canvas]") {
    render::Canvas canvas(40, 20);
    canvas.set_transparent(true);
    canvas.background({1, 1, 1, 1});
    render::Shapes shapes;
    shapes.rect({10, 5, 10, 10}, {1, 0, 0, 0.5f});
    shapes.rect({25, 5, 10, 10}, {0, 0, 1, 1});
    shapes.draw(canvas);
    const render::Image image = canvas.read();
    const std::uint8_t* corner = image.pixel(0, 0);
    CHECK(int(corner[3]) == 0);
    const std::uint8_t* half_red = image.pixel(15, 10);
    CHECK(int(half_red[0]) == 255);  // not 128: PNG's colour is not premultiplied
    CHECK(int(half_red[1]) == 0);
    CHECK(std::abs(int(half_red[3]) - 128) <= 1);
    const std::uint8_t* blue = image.pixel(30, 10);
    CHECK(int(blue[2]) == 255);
    CHECK(int(blue[3]) == 255);
}

TEST_CASE("the vector comparison passes a figure against itself and fails one with a panel gone", "[vector]") {
    render::Image figure(200, 100);
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 200; ++x) {
            std::uint8_t* p = figure.pixel(x, y);
            const bool ink = (x > 20 && x < 90 && y > 20 && y < 80) || (x > 110 && x < 180 && y > 20 && y < 80);
            p[0] = ink ? 30 : 255, p[1] = ink ? 90 : 255, p[2] = ink ? 160 : 255, p[3] = 255;
        }
    CHECK(testkit::block_difference(figure, figure).within_tolerance());
    render::Image gone = figure;
    for (int y = 20; y < 80; ++y)
        for (int x = 110; x < 180; ++x) std::fill(gone.pixel(x, y), gone.pixel(x, y) + 3, 255);
    const testkit::BlockDifference d = testkit::block_difference(figure, gone);
    INFO(d.message);
    CHECK(d.comparable);
    CHECK_FALSE(d.within_tolerance());
    render::Image smaller(190, 100);
    CHECK_FALSE(testkit::block_difference(figure, smaller).comparable);
}

TEST_CASE("a colour bar's tick labels span its field's range, at the bar's ends", "[vector][colour-bar]") {
    // A field from 0 to 0.25 with its bar, drawn on a vector page: the text
    // it holds is exactly what was drawn.
    sim::Grid<double> grid(2, 2);
    grid(0, 1) = 0.05, grid(1, 0) = 0.1, grid(1, 1) = 0.25;
    scenes::FieldSpec spec{render::colormap("Reds"), 0.0, 0.25, 1.0f, render::Sampling::nearest, true, "u"};
    const std::vector<scenes::FieldPanel> panels = {{"panel", {scenes::field_layer(grid, spec)}}};
    REQUIRE(panels[0].layers[0].colour_bar);
    CHECK(panels[0].layers[0].colour_bar->low == 0.0);
    CHECK(panels[0].layers[0].colour_bar->high == 0.25);
    render::VectorPage page(600, 400, false);
    description::Description d;
    d.width = 600, d.height = 400;
    scenes::field_figure(panels, d, scenes::SceneOptions{}).draw(page);
    std::vector<std::pair<std::string, float>> labels;  // tick labels and their baselines' y
    bool label = false;
    for (const auto& item : page.page().items)
        if (const auto* g = std::get_if<render::vector::Glyphs>(&item)) {
            if (g->text == "u") label = g->rotation_degrees == 90;
            else if (g->text != "panel") labels.emplace_back(g->text, g->origin.y);
        }
    CHECK(label);
    REQUIRE(labels.size() >= 3);
    CHECK(labels.front().first == "0.00");
    CHECK(labels.back().first == "0.25");
    for (const auto& [text, y] : labels) {
        const double v = std::stod(text);
        CHECK(v >= 0.0);
        CHECK(v <= 0.25);
    }
    // 0.00 at the bar's bottom, 0.25 at its top: the field's rectangle, as the bar stands beside it.
    std::vector<const render::vector::Picture*> pictures;  // the field's, then the bar's
    for (const auto& item : page.page().items)
        if (const auto* p = std::get_if<render::vector::Picture>(&item)) pictures.push_back(p);
    REQUIRE(pictures.size() == 2);
    const auto& field = *pictures[0];
    const float cap = render::font_of_size(14).cap_height() / 2;
    CHECK(std::abs(labels.front().second - cap - field.where.bottom()) < 1.5f);
    CHECK(std::abs(labels.back().second - cap - field.where.y) < 1.5f);
    // The bar's entries: the colormap, lowest at the bottom.
    const auto& bar = *pictures[1];
    CHECK(bar.image.height == 256);
    CHECK(bar.image.width == 1);
    const glm::vec3 top = render::colormap("Reds").at(1.0);
    CHECK(int(bar.image.pixel(0, 0)[0]) == int(std::lround(top.r * 255)));
}

TEST_CASE("hexagons under a pixel across are embedded as one image, larger ones as one path", "[vector]") {
    std::vector<glm::ivec2> cells;
    for (int q = -20; q <= 20; ++q)
        for (int r = -20; r <= 20; ++r) cells.push_back({q, r});
    render::VectorPage coarse(200, 200, false), fine(200, 200, false);
    render::draw_hex_cells(coarse, {{100, 100}, 2.0f}, cells, {0, 0, 1, 1});
    render::draw_hex_cells(fine, {{100, 100}, 0.5f}, cells, {0, 0, 1, 1});
    REQUIRE(coarse.page().items.size() == 1);
    const auto& path = std::get<render::vector::Fill>(coarse.page().items[0]).path;
    CHECK(path.size() == cells.size() * 7);  // six corners and a close each
    REQUIRE(fine.page().items.size() == 1);
    const auto& picture = std::get<render::vector::Picture>(fine.page().items[0]);
    CHECK(picture.image.width == 200);
    CHECK(picture.image.height == 200);
    CHECK(int(picture.image.pixel(100, 100)[2]) == 255);  // the lattice's centre, inked
    CHECK(int(picture.image.pixel(100, 100)[3]) == 255);
    CHECK(int(picture.image.pixel(0, 0)[3]) == 0);        // beyond it, clear
}
