// The gallery page: what `figgen gallery` writes for the figures in a folder.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "figgen_run.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"
#include "media/thumbnail.hpp"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

int count(const std::string& text, const std::string& part) {
    int n = 0;
    for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

// Mean absolute difference over the RGB channels of two same-size images.
double mean_difference(const render::Image& a, const render::Image& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        if (i % 4 != 3) sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    return sum / (a.rgba.size() / 4 * 3);
}

}  // namespace

TEST_CASE("thumbnails average the pixels they cover and keep the aspect ratio", "[gallery]") {
    render::Image image(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = x < 2 ? 255 : 0;          // left half white, right half black
            p[1] = std::uint8_t(x * 60);     // 0, 60, 120, 180: pairs average to 30 and 150
            p[2] = 100;
            p[3] = 255;
        }
    const render::Image half = media::thumbnail(image, 2, 100);
    REQUIRE(half.width == 2);
    REQUIRE(half.height == 1);
    CHECK(int(half.pixel(0, 0)[0]) == 255);
    CHECK(int(half.pixel(1, 0)[0]) == 0);
    CHECK(std::abs(int(half.pixel(0, 0)[1]) - 30) <= 1);
    CHECK(std::abs(int(half.pixel(1, 0)[1]) - 150) <= 1);
    CHECK(int(half.pixel(0, 0)[2]) == 100);
    // Already small enough: unchanged.
    CHECK(media::thumbnail(image, 10, 10).rgba == image.rgba);
    CHECK_THROWS_AS(media::thumbnail(image, 0, 10), std::invalid_argument);
}

TEST_CASE("figgen gallery shows every rendered figure with thumbnail, film, parameters and numbers", "[gallery][cli]") {
    const fs::path out = testkit::fresh_dir("gallery");
    REQUIRE(testkit::figgen("render tc7-1 tc7-9 --scale 0.5 --seed 4 --out " + out.string()).status == 0);
    const testkit::Run run = testkit::figgen("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("index.html: 2 figures"));
    const std::string page = slurp(out / "index.html");

    CHECK(count(page, "<article ") == 2);
    std::size_t catalog = 0;  // counted from the folder itself
    for (const auto& entry : fs::directory_iterator(fs::path(FIGGEN_SOURCE_DIR) / "figures"))
        catalog += entry.path().extension() == ".toml";
    CHECK(catalog > 30);
    CHECK_THAT(page, Catch::Contains("2 figures rendered by figgen") &&
                         Catch::Contains(std::to_string(catalog - 2) + " of the catalog not rendered here"));
    CHECK_THAT(page, Catch::Contains("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"));
    // Nothing from the network: every src and href is a file in the folder
    // (or the empty data: icon that keeps the browser from asking for one).
    CHECK_FALSE(std::regex_search(page, std::regex("(src|href)=\"(?!data:,\")[a-z]+:")));
    CHECK(count(page, "<script") == 0);

    std::ifstream in(out / "tc7-1.json");
    const auto meta = nlohmann::json::parse(in);
    // The thumbnail: a real file, its size in the tag, within 480 x 360.
    const auto thumb = media::read_png(out / "thumbs" / "tc7-1.png").image;
    CHECK(thumb.width <= 480);
    CHECK(thumb.height <= 360);
    CHECK_THAT(page, Catch::Contains("<img src=\"thumbs/tc7-1.png\" width=\"" + std::to_string(thumb.width) +
                                     "\" height=\"" + std::to_string(thumb.height) + "\""));
    // The film, with the frame count and size of its metadata; tc7-9 has none.
    const auto& film = meta["animation"];
    // Its poster: the frame of the step its description names (tc7-1.toml:
    // poster = 8, the block spread into a bump), decoded from the film.
    REQUIRE(film["poster"]["step"] == 8);
    const int poster_frame = film["poster"]["frame"].get<int>();
    CHECK(film["steps"][poster_frame] == 8);
    CHECK_THAT(page, Catch::Contains("<video controls preload=\"metadata\" src=\"tc7-1.mp4\" poster=\"posters/tc7-1.png\" width=\"" +
                                     std::to_string(film["size"][0].get<int>()) + "\""));
    CHECK_THAT(page, Catch::Contains("data-frames=\"" + std::to_string(film["frames"].get<int>()) + "\""));
    CHECK_THAT(page, Catch::Contains("data-poster-frame=\"" + std::to_string(poster_frame) + "\""));
    CHECK(count(page, "<video ") == 1);
    // The film's card shows its animated preview (issue "Publication and web
    // outputs") until the film is opened to play: the preview at the size
    // its header and metadata give, as the summary of a <details> that
    // holds the <video>, whose poster stays the poster frame.
    const media::PreviewInfo preview = media::probe_preview(out / "tc7-1.webp");
    CHECK(film["preview"]["file"] == "tc7-1.webp");
    CHECK(film["preview"]["size"] == nlohmann::json::array({preview.width, preview.height}));
    CHECK(preview.frames > 1);
    const auto opened =
        page.find("<details class=\"film\"><summary><img class=\"preview\" src=\"tc7-1.webp\" width=\"" +
                  std::to_string(preview.width) + "\" height=\"" + std::to_string(preview.height) + "\"");
    REQUIRE(opened != std::string::npos);
    const auto video = page.find("<video ", opened), closed = page.find("</details>", opened);
    CHECK(video < closed);
    CHECK(page.find("</summary>", opened) < video);
    CHECK(count(page, "class=\"preview\"") == 1);  // tc7-9 has no film, no preview
    // Source, seed, parameters and the numbers computed.
    CHECK_THAT(page, Catch::Contains("Think Complexity"));
    CHECK_THAT(page, Catch::Contains("<tr><th>seed</th><td>4</td></tr>"));
    CHECK_THAT(page, Catch::Contains("<tr><th>r</th><td>0.1</td></tr>"));
    CHECK_THAT(page, Catch::Contains("<tr><th>panels.0.statistics.sum</th><td>9</td></tr>"));
    CHECK_THAT(page, Catch::Contains("<a href=\"tc7-1.png\">full PNG (" +
                                     std::to_string(meta["image"]["size"][0].get<int>()) + " x "));

    const testkit::Run bad = testkit::figgen("gallery --out " + (out / "nope").string());
    CHECK(bad.status == 2);
    CHECK_THAT(bad.output, Catch::Contains("is not a folder of rendered figures"));
}

TEST_CASE("figgen thumbnails makes a film's preview an animated thumbnail of the same duration", "[gallery][cli][preview]") {
    const fs::path out = testkit::fresh_dir("animated-thumbs"), thumbs = testkit::fresh_dir("animated-thumbs-to");
    REQUIRE(testkit::figgen("render tc7-1 tc7-9 --scale 0.5 --out " + out.string()).status == 0);
    const testkit::Run run =
        testkit::figgen("thumbnails --from " + out.string() + " --to " + thumbs.string() + " --width 120 --height 90");
    INFO(run.output);
    REQUIRE(run.status == 0);
    const media::PreviewInfo preview = media::probe_preview(out / "tc7-1.webp");
    const media::PreviewInfo thumb = media::probe_preview(thumbs / "tc7-1.webp");
    // The preview's 240 x 260 fitted into 120 x 90: 83 x 90; 24 of its 48 frames.
    CHECK(thumb.width == 83);
    CHECK(thumb.height == 90);
    CHECK(thumb.frames == 24);
    CHECK(thumb.loop_count == 0);
    CHECK(thumb.duration_ms == preview.duration_ms);
    CHECK(thumb.bytes <= 400u << 10);
    // Its last frame is the preview's, scaled: the same mean colour.
    const render::Image last = media::decode_preview_frame(thumbs / "tc7-1.webp", 23);
    const render::Image big = media::decode_preview_frame(out / "tc7-1.webp", 47);
    for (int c = 0; c < 3; ++c) {
        double small_mean = 0, big_mean = 0;
        for (std::size_t i = c; i < last.rgba.size(); i += 4) small_mean += last.rgba[i];
        for (std::size_t i = c; i < big.rgba.size(); i += 4) big_mean += big.rgba[i];
        CHECK(small_mean / (last.rgba.size() / 4) == Approx(big_mean / (big.rgba.size() / 4)).margin(3));
    }
    CHECK(fs::exists(thumbs / "tc7-9.png"));
    CHECK_FALSE(fs::exists(thumbs / "tc7-9.webp"));  // no film, no animated thumbnail
}

TEST_CASE("gallery poster is the frame the description names and else the last frame", "[gallery][cli]") {
    const fs::path out = testkit::fresh_dir("gallery-poster");
    // tc7-1 names step 8; the same film every third step, whose frames pass
    // step 8 (poster: step 6, the last before it); tc7-5 names none.
    REQUIRE(testkit::figgen("render tc7-1 tc7-5 --scale 0.5 --format mp4,frames --out " + out.string()).status == 0);
    const fs::path other = out / "other";
    REQUIRE(testkit::figgen("render tc7-1 --scale 0.5 --set id=tc7-1-early --set animation.stride=3 --out " +
                            other.string()).status == 0);
    fs::copy_file(other / "tc7-1-early.json", out / "tc7-1-early.json");
    fs::copy_file(other / "tc7-1-early.png", out / "tc7-1-early.png");
    fs::copy_file(other / "tc7-1-early.mp4", out / "tc7-1-early.mp4");
    const testkit::Run run = testkit::figgen("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    const std::string page = slurp(out / "index.html");
    struct Poster {
        std::string id;
        int frame, step;  // -1: the last
    };
    for (const auto& [id, frame_named, step] :
         {Poster{"tc7-1", 8, 8}, Poster{"tc7-1-early", 2, 6}, Poster{"tc7-5", -1, -1}}) {
        INFO(id);
        std::ifstream in(out / (id + ".json"));
        const auto film = nlohmann::json::parse(in)["animation"];
        const int frames = film["frames"].get<int>(), frame = film["poster"]["frame"].get<int>();
        // The metadata names the frame of the step; without one, the last.
        CHECK(film["poster"]["step"] == film["steps"][frame]);
        CHECK(frame == (frame_named < 0 ? frames - 1 : frame_named));
        if (step >= 0) CHECK(film["poster"]["step"] == step);
        CHECK_THAT(page, Catch::Contains("src=\"" + id + ".mp4\" poster=\"posters/" + id + ".png\""));
        CHECK_THAT(page, Catch::Contains("data-poster-frame=\"" + std::to_string(frame) + "\""));
        // The poster is that frame of the film as a browser decodes it, and
        // the same render's lossless frame within H.264's loss.
        const auto poster = media::read_png(out / "posters" / (id + ".png")).image;
        const auto decoded = media::decode_frame(out / (id + ".mp4"), frame);
        REQUIRE(poster.width == film["size"][0].get<int>());
        REQUIRE(poster.height == film["size"][1].get<int>());
        REQUIRE(decoded.width == poster.width);
        CHECK(mean_difference(poster, decoded) < 0.01);
        if (id == "tc7-1-early") continue;  // its frames are in the other folder's film only
        char name[16];
        std::snprintf(name, sizeof name, "%05d.png", frame);
        const auto lossless = media::read_png(out / (id + "-frames") / name).image;
        CHECK(mean_difference(poster, lossless) < 1.5);
        if (step >= 0) {
            std::snprintf(name, sizeof name, "%05d.png", frames - 1);
            const auto last = media::read_png(out / (id + "-frames") / name).image;
            CHECK(mean_difference(poster, last) > 5 * mean_difference(poster, lossless));
        }
    }
    // A second gallery keeps a poster decoded from the same film at the same
    // frame; a film rendered again, or another frame named, is decoded anew.
    const auto kept = fs::last_write_time(out / "posters" / "tc7-1-early.png");
    REQUIRE(testkit::figgen("render tc7-1 --scale 0.5 --set animation.poster=20 --out " + out.string()).status == 0);
    std::ifstream in(out / "tc7-5.json");
    nlohmann::json edited = nlohmann::json::parse(in);
    edited["animation"]["poster"] = {{"frame", 2}, {"step", 2}};
    std::ofstream(out / "tc7-5.json") << edited.dump();
    REQUIRE(testkit::figgen("gallery --out " + out.string()).status == 0);
    CHECK(fs::last_write_time(out / "posters" / "tc7-1-early.png") == kept);
    for (const auto& [id, frame] : {std::pair{std::string("tc7-1"), 20}, {std::string("tc7-5"), 2}}) {
        INFO(id);
        CHECK(mean_difference(media::read_png(out / "posters" / (id + ".png")).image,
                              media::decode_frame(out / (id + ".mp4"), frame)) < 0.01);
    }
}
