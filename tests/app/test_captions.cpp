// Text in the documents' own scripts, as a user meets it: each document's
// printed caption drawn beneath its figure ([figure] caption = "original"),
// shaped from the fallback face fontconfig finds, with no warning; a
// character no font has named in a warning; a progress bar that fits the
// terminal.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "media/png_io.hpp"
#include "vector_check.hpp"

namespace fs = std::filesystem;

namespace {

nlohmann::json metadata(const fs::path& file) { return nlohmann::json::parse(testkit::slurp(file)); }

// The rows at the bottom of `image` that hold ink darker than mid grey.
int dark_pixels(const render::Image& image, int from_row) {
    int dark = 0;
    for (int y = from_row; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) dark += image.pixel(x, y)[1] < 128 ? 1 : 0;
    return dark;
}

}  // namespace

TEST_CASE("each document's own caption is drawn beneath its figure in its script", "[cli][text]") {
    const fs::path out = testkit::fresh_dir("original-captions");
    struct Case {
        const char* id;
        const char* caption;  // as the description gives it, from the seed document
        const char* language;
        const char* face;     // the PDF's subset of Noto Sans CJK for that language
        int width, height;    // at scale 0.5
    };
    for (const Case& c : {Case{"sf87-3", "图 3 “奇偶规则”生长出的雪花瞬时图象", "zh-cn", "NotoSansCJKsc", 450, 250},
                          Case{"pl-lsys-apple", "由数学规则生成的苹果树,迭代次数为n=4", "zh-cn", "NotoSansCJKsc", 500, 310},
                          Case{"bd-500", "なんか山並み感ありませんか?", "ja", "NotoSansCJKjp", 350, 500}}) {
        INFO(c.id);
        const testkit::Run run = testkit::figgen(std::string("render ") + c.id +
                                                 " --set figure.caption=original --scale 0.5 --format png,pdf --out " +
                                                 out.string());
        REQUIRE(run.status == 0);
        CHECK(run.output.find("warning") == std::string::npos);
        const nlohmann::json meta = metadata(out / (std::string(c.id) + ".json"));
        const nlohmann::json& caption = meta["figure_caption"];
        CHECK(caption["lines"] == nlohmann::json::array({c.caption}));
        CHECK(caption["language"] == c.language);
        // The band is taken from the figure, which keeps its size.
        const render::Image png = media::read_png(out / (std::string(c.id) + ".png")).image;
        CHECK(png.width == c.width);
        CHECK(png.height == c.height);
        const int band = caption["band"].get<int>();
        CHECK(band > 0);
        CHECK(band < c.height / 3);
        CHECK(dark_pixels(png, c.height - band) > 100);  // glyphs, not an empty band
        // The PDF embeds the language's face and reads back as the caption.
        const fs::path pdf = out / (std::string(c.id) + ".pdf");
        bool face = false;
        for (const auto& f : testkit::pdf_fonts(pdf)) {
            CHECK(f.embedded);
            face = face || f.name.find(c.face) != std::string::npos;
        }
        CHECK(face);
        const testkit::ToolRun text = testkit::run_tool("pdftotext '" + pdf.string() + "' -");
        REQUIRE(text.status == 0);
        CHECK(text.output.find(c.caption) != std::string::npos);
    }
}

TEST_CASE("a caption with a character no font has renders with a warning naming it", "[cli][text]") {
    const fs::path out = testkit::fresh_dir("caption-private-use");
    const fs::path file = out / "private.toml";
    std::ofstream(file) << "id = \"private\"\nscene = \"diffusion\"\n"
                           "original_caption = \"seal \u5370 \uE000 here\"\nlanguage = \"zh-cn\"\n"
                           "[figure]\ncaption = \"original\"\npanels = [0]\n";
    const testkit::Run run = testkit::figgen("render --no-video --out " + out.string() + " " + file.string());
    REQUIRE(run.status == 0);
    CHECK(run.output.find("figgen: warning: no installed font has U+E000") != std::string::npos);
    CHECK(run.output.find("U+5370") == std::string::npos);  // the ideograph is found
    CHECK(fs::exists(out / "private.png"));
}

TEST_CASE("the title as a caption wraps to the figure's width", "[cli][text]") {
    const fs::path out = testkit::fresh_dir("caption-title");
    REQUIRE(testkit::figgen("render tc7-9 --set figure.caption=title --size 300x400 --out " + out.string()).status == 0);
    const nlohmann::json caption = metadata(out / "tc7-9.json")["figure_caption"];
    REQUIRE(caption["lines"].size() >= 2);
    std::string joined;
    for (const auto& line : caption["lines"]) {
        if (!joined.empty()) joined.push_back(' ');
        joined.append(line.get<std::string>());
    }
    CHECK(joined == metadata(out / "tc7-9.json")["title"]);
    const render::Image png = media::read_png(out / "tc7-9.png").image;
    CHECK(png.height == 400);
}

TEST_CASE("the progress bar fits the terminal's width", "[cli]") {
    const fs::path out = testkit::fresh_dir("progress-width");
    for (const int columns : {80, 50, 24}) {
        INFO(columns << " columns");
        // script(1) gives figgen a terminal of that width.
        const testkit::Run run = testkit::run_command("script -qec \"stty cols " + std::to_string(columns) + "; " +
                                                      FIGGEN_EXE + " render tc7-1 --scale 0.5 --out " + out.string() +
                                                      "\" /dev/null");
        REQUIRE(run.status == 0);
        int bars = 0;
        std::string segment;
        for (const char c : run.output + "\n") {
            if (c != '\r' && c != '\n') {
                segment.push_back(c);
                continue;
            }
            if (segment.find('%') != std::string::npos) {
                ++bars;
                CHECK(static_cast<int>(segment.size()) < columns);  // ASCII: a byte a column
            }
            segment.clear();
        }
        CHECK(bars > 0);
        CHECK(run.output.find("100%") != std::string::npos);
    }
}
