// What `figgen gallery` and `figgen thumbnails` do with files that someone
// else put in the folder: images whose headers claim far more pixels than
// they hold (refused for their card from the header, before decoding, under
// --max-memory), FIFOs where a file should be (never waited on), and JSON
// nested a million levels deep (refused by the depth limit, no crash).
// Memory is not measured here: the refusal and what the card says are.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "figgen_run.hpp"
#include "media/png_io.hpp"
#include "media/video.hpp"

namespace fs = std::filesystem;
using testkit::slurp;
using testkit::spill;

namespace {

// tc7-1 (a film, its preview) and tc7-9 (no film) rendered once per
// process at half size, as figgen writes them.
const fs::path& rendered() {
    static const fs::path out = [] {
        const fs::path folder = testkit::fresh_dir("gallery-inputs-rendered");
        const testkit::Run run = testkit::figgen("render tc7-1 tc7-9 --scale 0.5 --out " + folder.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        return folder;
    }();
    return out;
}

// A fresh copy of them for one test to spoil.
fs::path rendered_copy(const std::string& name) {
    const fs::path out = testkit::fresh_dir(name);
    fs::copy(rendered(), out, fs::copy_options::recursive);
    return out;
}

// PNG's CRC-32 (ISO 3309), bit by bit: a few chunks only.
std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (const unsigned char byte : bytes) {
        crc ^= byte;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xffffffffu;
}

void put_be32(std::string& bytes, std::size_t at, std::uint32_t value) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((value >> (24 - 8 * i)) & 0xff);
}

// A real PNG of figgen's whose IHDR is made to claim width x height (its
// CRC made good again): a file of a few KB that a reader trusting its
// header would decode into width * height * 4 bytes.
void claim_png_size(const fs::path& png, std::uint32_t width, std::uint32_t height) {
    std::string bytes = slurp(png);
    REQUIRE(bytes.compare(12, 4, "IHDR") == 0);  // the first chunk, after the 8-byte signature and its length
    put_be32(bytes, 16, width);
    put_be32(bytes, 20, height);
    put_be32(bytes, 29, crc32(bytes.substr(12, 17)));  // type and the 13 bytes of data
    spill(png, bytes);
}

// The animated WebP's VP8X chunk made to claim a canvas of width x height
// (24 bits each, less one, little-endian at bytes 24..29).
void claim_webp_size(const fs::path& webp, std::uint32_t width, std::uint32_t height) {
    std::string bytes = slurp(webp);
    REQUIRE(bytes.compare(12, 4, "VP8X") == 0);
    for (int i = 0; i < 3; ++i) {
        bytes[24 + i] = static_cast<char>(((width - 1) >> (8 * i)) & 0xff);
        bytes[27 + i] = static_cast<char>(((height - 1) >> (8 * i)) & 0xff);
    }
    spill(webp, bytes);
}

// The MP4's visual sample entry in its stsd box (avc1, or mp4v for the
// MPEG-4 fallback) made to claim frames of width x height: its 16-bit width
// and height 24 bytes after the entry's type, what libavformat gives as the
// stream's size before any frame is decoded.
void claim_mp4_size(const fs::path& mp4, std::uint16_t width, std::uint16_t height) {
    std::string bytes = slurp(mp4);
    const std::size_t entries = bytes.find("stsd");  // past the ftyp box, whose brands name avc1 too
    REQUIRE(entries != std::string::npos);
    std::size_t at = bytes.find("avc1", entries);
    if (at == std::string::npos) at = bytes.find("mp4v", entries);
    REQUIRE(at != std::string::npos);
    for (const auto& [offset, value] : {std::pair{28u, width}, std::pair{30u, height}}) {
        bytes[at + offset] = static_cast<char>(value >> 8);
        bytes[at + offset + 1] = static_cast<char>(value & 0xff);
    }
    spill(mp4, bytes);
}

// The <article> of figure `id` in the page, or "".
std::string card_of(const std::string& page, const std::string& id) {
    const auto begin = page.find("<article id=\"" + id + "\">");
    if (begin == std::string::npos) return "";
    return page.substr(begin, page.find("</article>", begin) - begin);
}

// `figgen args`, ended after 60 s if it hangs (timeout's exit status 124).
testkit::Run figgen_in_time(const std::string& args) {
    return testkit::run_command("timeout -s KILL 60 " + std::string(FIGGEN_EXE) + " " + args);
}

}  // namespace

TEST_CASE("gallery refuses a PNG, a film and a preview whose headers claim too many pixels, card by card",
          "[gallery][cli][bounds]") {
    const fs::path out = rendered_copy("gallery-bombs");
    // tc7-9's PNG claims 20000 x 20000 (1.6 GB of RGBA; the file is a few KB).
    claim_png_size(out / "tc7-9.png", 20000, 20000);
    // tc7-1's film claims 20000 x 20000 frames, its preview a 16000 x 16000 canvas.
    claim_mp4_size(out / "tc7-1.mp4", 20000, 20000);
    claim_webp_size(out / "tc7-1.webp", 16000, 16000);
    fs::remove_all(out / "posters");  // no poster kept from before: the film must be read
    const testkit::Run run = figgen_in_time("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("index.html: 2 figures"));
    const std::string page = slurp(out / "index.html");

    // Each card is made, and says why in its image's place.
    const std::string plain = card_of(page, "tc7-9");
    REQUIRE_FALSE(plain.empty());
    CHECK_THAT(plain, Catch::Contains("<p class=\"refused\">tc7-9.png is not decoded: its header claims 20000 x 20000 "
                                      "pixels, which would take about "));
    CHECK_THAT(plain, Catch::Contains("to decode, more than --max-memory 1.0 GiB</p>"));
    CHECK(plain.find("<img") == std::string::npos);
    CHECK_THAT(plain, Catch::Contains("<details><summary>parameters"));  // the rest of the card is there
    CHECK_FALSE(fs::exists(out / "thumbs" / "tc7-9.png"));

    const std::string film = card_of(page, "tc7-1");
    REQUIRE_FALSE(film.empty());
    CHECK_THAT(film, Catch::Contains("<img src=\"thumbs/tc7-1.png\""));  // its PNG is honest
    CHECK_THAT(film, Catch::Contains("<p class=\"refused\">tc7-1.mp4 is not decoded: its header claims 20000 x 20000 "
                                     "pixels"));
    CHECK(film.find("<video") == std::string::npos);
    CHECK_FALSE(fs::exists(out / "posters" / "tc7-1.png"));

    // The film honest again, its preview still lying: the film is shown
    // with its poster frame, the preview refused in its card.
    fs::copy_file(rendered() / "tc7-1.mp4", out / "tc7-1.mp4", fs::copy_options::overwrite_existing);
    const testkit::Run again = figgen_in_time("gallery --out " + out.string());
    INFO(again.output);
    REQUIRE(again.status == 0);
    const std::string second = card_of(slurp(out / "index.html"), "tc7-1");
    CHECK_THAT(second,
               Catch::Contains("<video controls preload=\"metadata\" src=\"tc7-1.mp4\" poster=\"posters/tc7-1.png\""));
    CHECK_THAT(second,
               Catch::Contains("<p class=\"refused\">tc7-1.webp is not decoded: its header claims 16000 x 16000 "
                               "pixels"));
    CHECK(second.find("img class=\"preview\"") == std::string::npos);
}

TEST_CASE("gallery and thumbnails take --max-memory and hold an image's header to it", "[gallery][cli][bounds]") {
    const fs::path out = rendered_copy("gallery-max-memory"), thumbs = testkit::fresh_dir("gallery-max-memory-thumbs");
    // A real PNG of 3000 x 3000 as tc7-9's: 9 Mpx, about 40 MiB of RGBA
    // and the program's 64 MiB: more than 80M, well within 1G.
    render::Image big(3000, 3000);
    for (std::size_t i = 0; i < big.rgba.size(); ++i) big.rgba[i] = i % 4 == 3 ? 255 : 200;
    media::write_png(out / "tc7-9.png", big);

    const testkit::Run tight = figgen_in_time("gallery --out " + out.string() + " --max-memory 80M");
    INFO(tight.output);
    REQUIRE(tight.status == 0);
    CHECK_THAT(card_of(slurp(out / "index.html"), "tc7-9"),
               Catch::Contains("tc7-9.png is not decoded: its header claims 3000 x 3000 pixels") &&
                   Catch::Contains("more than --max-memory 80.0 MiB"));
    const testkit::Run roomy = figgen_in_time("gallery --out " + out.string() + " --max-memory 1G");
    INFO(roomy.output);
    REQUIRE(roomy.status == 0);
    const std::string card = card_of(slurp(out / "index.html"), "tc7-9");
    CHECK(card.find("class=\"refused\"") == std::string::npos);
    CHECK_THAT(card, Catch::Contains("<img src=\"thumbs/tc7-9.png\" width=\"360\" height=\"360\""));

    // thumbnails: the file refused is named on stderr and the run fails;
    // the others are written.
    const std::string to = " --from " + out.string() + " --to " + thumbs.string();
    const testkit::Run refused = figgen_in_time("thumbnails" + to + " --max-memory 80M");
    INFO(refused.output);
    CHECK(refused.status == 2);
    CHECK_THAT(refused.output, Catch::Contains("figgen: error: " + (out / "tc7-9.png").string() +
                                               " is not decoded: its header claims 3000 x 3000 pixels"));
    CHECK(fs::exists(thumbs / "tc7-1.png"));
    CHECK(fs::exists(thumbs / "tc7-1.webp"));
    CHECK_FALSE(fs::exists(thumbs / "tc7-9.png"));
    const testkit::Run made = figgen_in_time("thumbnails" + to + " --max-memory 1G");
    INFO(made.output);
    CHECK(made.status == 0);
    CHECK(media::read_png(thumbs / "tc7-9.png").image.width == 180);

    // The option is read as render's is.
    for (const std::string& command : {"gallery --out " + out.string(), "thumbnails" + to}) {
        const testkit::Run bad = figgen_in_time(command + " --max-memory 0");
        CHECK(bad.status == 2);
        CHECK_THAT(bad.output, Catch::Contains("--max-memory 0 is not allowed: use a size from 1 byte to 1 PiB"));
    }
}

TEST_CASE("thumbnails refuses a bomb PNG and a bomb preview from their headers and makes the rest",
          "[gallery][cli][bounds]") {
    const fs::path out = rendered_copy("thumbnail-bombs"), thumbs = testkit::fresh_dir("thumbnail-bombs-to");
    claim_png_size(out / "tc7-9.png", 20000, 20000);
    claim_webp_size(out / "tc7-1.webp", 16000, 16000);
    const testkit::Run run =
        figgen_in_time("thumbnails --from " + out.string() + " --to " + thumbs.string() + " --width 120 --height 90");
    INFO(run.output);
    CHECK(run.status == 2);
    CHECK_THAT(run.output, Catch::Contains((out / "tc7-9.png").string() +
                                           " is not decoded: its header claims 20000 x 20000 pixels"));
    CHECK_THAT(run.output, Catch::Contains((out / "tc7-1.webp").string() +
                                           " is not decoded: its header claims 16000 x 16000 pixels"));
    CHECK(media::read_png(thumbs / "tc7-1.png").image.width == 120);  // 450 x 225 fitted into 120 x 90
    CHECK_FALSE(fs::exists(thumbs / "tc7-9.png"));
    CHECK_FALSE(fs::exists(thumbs / "tc7-1.webp"));
}

TEST_CASE("gallery and thumbnails never wait on a FIFO where a figure's file should be", "[gallery][cli][bounds]") {
    const fs::path out = rendered_copy("gallery-fifos"), thumbs = testkit::fresh_dir("gallery-fifos-thumbs");
    // tc7-9's metadata and tc7-1's PNG, film and preview are FIFOs: opening
    // any of them to read would wait for a writer for ever.
    for (const std::string name : {"tc7-9.json", "tc7-1.png", "tc7-1.mp4", "tc7-1.webp"}) {
        fs::remove(out / name);
        REQUIRE(::mkfifo((out / name).c_str(), 0644) == 0);
    }
    const testkit::Run run = figgen_in_time("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);  // not 137: timeout's KILL
    const std::string page = slurp(out / "index.html");
    CHECK_THAT(page, Catch::Contains("could not show tc7-9: tc7-9.json is not a regular file"));
    CHECK_THAT(page, Catch::Contains("could not show tc7-1: tc7-1.png is not a regular file"));
    CHECK(page.find("<article ") == std::string::npos);

    const testkit::Run thumbnails = figgen_in_time("thumbnails --from " + out.string() + " --to " + thumbs.string());
    INFO(thumbnails.output);
    CHECK(thumbnails.status == 0);
    CHECK_THAT(thumbnails.output, Catch::Contains(": 1 thumbnails"));  // tc7-9's; tc7-1's PNG is a FIFO, passed over
    CHECK(fs::exists(thumbs / "tc7-9.png"));
    CHECK_FALSE(fs::exists(thumbs / "tc7-1.png"));
}

TEST_CASE("gallery refuses metadata nested a million levels deep without a crash", "[gallery][cli][bounds]") {
    const fs::path out = rendered_copy("gallery-deep");
    const std::string nest = std::string(1000000, '[') + std::string(1000000, ']');
    // The catalog's tc7-9, and a figure outside the catalog, each with a
    // parameter a million levels deep.
    for (const std::string id : {"tc7-9", "deep"}) {
        nlohmann::json meta = nlohmann::json::parse(slurp(out / "tc7-9.json"));
        meta["id"] = id;
        meta["params"]["nested"] = "NEST";
        std::string text = meta.dump();
        text.replace(text.find("\"NEST\""), 6, nest);
        spill(out / (id + ".json"), text);
        if (id != "tc7-9") fs::copy_file(out / "tc7-9.png", out / (id + ".png"));
    }
    // And one 20 levels deep: within the limit, shown cut at 8 levels.
    nlohmann::json shallow = nlohmann::json::parse(slurp(out / "tc7-1.json"));
    shallow["params"]["nested"] = "NEST";
    std::string text = shallow.dump();
    text.replace(text.find("\"NEST\""), 6, std::string(20, '[') + "1" + std::string(20, ']'));
    spill(out / "tc7-1.json", text);

    const testkit::Run run = figgen_in_time("gallery --out " + out.string());
    INFO(run.output);
    REQUIRE(run.status == 0);
    CHECK_THAT(run.output, Catch::Contains("index.html: 1 figures"));
    const std::string page = slurp(out / "index.html");
    CHECK_THAT(page, Catch::Contains("could not show tc7-9: tc7-9.json nests arrays and objects more than 64 deep"));
    CHECK_THAT(page, Catch::Contains("could not show deep: deep.json nests arrays and objects more than 64 deep"));
    CHECK(card_of(page, "tc7-9").empty());
    CHECK(card_of(page, "deep").empty());
    CHECK_THAT(card_of(page, "tc7-1"), Catch::Contains("<tr><th>nested</th><td>[[[[[[[[[...]]]]]]]]]</td></tr>"));
}
