#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "base/atomic_file.hpp"
#include "media/video.hpp"

namespace fs = std::filesystem;
using render::Image;
using media::VideoOptions;
using media::VideoWriter;

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr int kFrames = 25;
constexpr int kBarWidth = 8;
constexpr std::uint8_t kBackground[3] = {40, 90, 200};  // blue

// Frame i: a white vertical bar, kBarWidth wide, starting at x = 2i, on blue.
Image moving_bar(int i) {
    Image image(kWidth, kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            const bool bar = x >= 2 * i && x < 2 * i + kBarWidth;
            for (int c = 0; c < 3; ++c) p[c] = bar ? 255 : kBackground[c];
            p[3] = 255;
        }
    return image;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(FIGGEN_TEST_ARTIFACT_DIR) / "video";
    fs::create_directories(dir);
    const fs::path path = dir / name;
    fs::remove(path);
    return path;
}

std::string encode_bar(const fs::path& path, const VideoOptions& options = {}) {
    VideoWriter writer(path, kWidth, kHeight, options);
    for (int i = 0; i < kFrames; ++i) writer.add(moving_bar(i));
    CHECK(writer.frames() == kFrames);
    writer.finish();
    return writer.codec_name();
}

// Mean of one channel over the columns [x0, x1) of the whole height.
double mean_channel(const Image& image, int x0, int x1, int channel) {
    double sum = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = x0; x < x1; ++x) sum += image.pixel(x, y)[channel];
    return sum / (double(x1 - x0) * image.height);
}

double mean_luma(const Image& image, int x0, int x1) {  // BT.709 weights
    return 0.2126 * mean_channel(image, x0, x1, 0) + 0.7152 * mean_channel(image, x0, x1, 1) +
           0.0722 * mean_channel(image, x0, x1, 2);
}

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Files in `path`'s folder named for `path`: the final file and any
// temporary (".<name>~tmp~<pid>~<n>").
int files_named_like(const fs::path& path) {
    const std::string name = path.filename().string();
    int n = 0;
    for (const auto& entry : fs::directory_iterator(path.parent_path())) {
        const std::string found = entry.path().filename().string();
        n += found == name || found.rfind("." + name + "~", 0) == 0;
    }
    return n;
}

}  // namespace

TEST_CASE("an encoded video decodes back to its frame count, size, format and duration", "[video]") {
    const fs::path path = scratch("bar.mp4");
    const std::string codec = encode_bar(path);
    CHECK((codec == "libx264" || codec == "mpeg4"));
    REQUIRE(fs::exists(path));
    const media::VideoInfo info = media::probe_video(path);
    CHECK(info.frames == kFrames);
    CHECK(info.width == kWidth);
    CHECK(info.height == kHeight);
    CHECK(info.pixel_format == "yuv420p");
    CHECK(info.codec == (codec == "libx264" ? "h264" : "mpeg4"));
    CHECK(info.fps == Approx(30.0));
    CHECK(info.duration_seconds == Approx(kFrames / 30.0).margin(0.5 / 30));
    CHECK(files_named_like(path) == 1);  // no temporary left beside it
}

TEST_CASE("a decoded frame keeps the pattern's colours and position", "[video]") {
    const fs::path path = scratch("bar_colour.mp4");
    encode_bar(path);
    const Image frame = media::decode_frame(path, 12);  // bar at x = 24..31
    REQUIRE(frame.width == kWidth);
    REQUIRE(frame.height == kHeight);
    // Inside the bar, away from its edges: white.
    CHECK(mean_luma(frame, 26, 30) == Approx(255).margin(4));
    // Far from the bar: the blue background, channel by channel.
    for (int c = 0; c < 3; ++c) CHECK(mean_channel(frame, 40, 60, c) == Approx(kBackground[c]).margin(4));
    CHECK(mean_luma(frame, 2, 20) ==
          Approx(0.2126 * kBackground[0] + 0.7152 * kBackground[1] + 0.0722 * kBackground[2]).margin(3));
    // The bar of frame 11 (x = 22..29) or 13 (x = 26..33) would light these.
    CHECK(mean_luma(frame, 20, 22) < 120);
    CHECK(mean_luma(frame, 34, 36) < 120);
    CHECK(mean_luma(frame, 24, 25) > 200);
    CHECK(mean_luma(frame, 31, 32) > 200);
    CHECK_THROWS_AS(media::decode_frame(path, kFrames), std::out_of_range);
}

// The media module returns its failures through a C error record
// (media/media_abi.h); the program throws them again as what they were.
TEST_CASE("the media module's failures come back as the exceptions they were", "[video]") {
    const fs::path path = scratch("bar_too_large.mp4");
    encode_bar(path);
    const base::Folder folder = base::Folder::of(path);
    const std::uint64_t allowed = static_cast<std::uint64_t>(kWidth) * kHeight - 1;
    try {
        media::decode_frame(folder, path.filename().string(), 0, 1, allowed);
        FAIL("a film larger than max_pixels decoded");
    } catch (const render::ImageTooLarge& e) {
        CHECK(e.width == static_cast<std::uint64_t>(kWidth));
        CHECK(e.height == static_cast<std::uint64_t>(kHeight));
        CHECK(e.max_pixels == allowed);
        CHECK_THAT(e.file, Catch::Contains("bar_too_large.mp4"));
        CHECK_THAT(e.what(), Catch::Contains("more than the " + std::to_string(allowed) + " allowed"));
    }
    CHECK(media::decode_frame(folder, path.filename().string(), 0, 1, allowed + 1).width == kWidth);
    CHECK_THROWS_AS(media::decode_frame(path, kFrames), std::out_of_range);
    CHECK_THROWS_AS(media::probe_video(scratch("no-such-film.mp4")), std::runtime_error);
}

TEST_CASE("decoding on more threads gives the same pixels", "[video]") {
    const fs::path path = scratch("bar_threads.mp4");
    encode_bar(path);
    const Image one = media::decode_frame(path, kFrames - 1, 1);
    for (const int threads : {0, 2, 3}) {
        INFO("threads " << threads);
        const Image many = media::decode_frame(path, kFrames - 1, threads);
        CHECK(many.width == one.width);
        CHECK(many.height == one.height);
        CHECK(many.rgba == one.rgba);
    }
    CHECK_THROWS_WITH(media::decode_frame(path, 0, -1), "decoder threads -1 is negative");
}

TEST_CASE("the mpeg4 fallback encodes the same frames", "[video]") {
    const fs::path path = scratch("bar_mpeg4.mp4");
    VideoOptions options;
    options.codec = "mpeg4";
    options.fps = 25;
    CHECK(encode_bar(path, options) == "mpeg4");
    const media::VideoInfo info = media::probe_video(path);
    CHECK(info.frames == kFrames);
    CHECK(info.width == kWidth);
    CHECK(info.height == kHeight);
    CHECK(info.pixel_format == "yuv420p");
    CHECK(info.codec == "mpeg4");
    CHECK(info.fps == Approx(25.0));
    CHECK(info.duration_seconds == Approx(1.0).margin(0.5 / 25));
    const Image frame = media::decode_frame(path, 12);
    CHECK(mean_luma(frame, 26, 30) == Approx(255).margin(6));
    for (int c = 0; c < 3; ++c) CHECK(mean_channel(frame, 40, 60, c) == Approx(kBackground[c]).margin(6));
}

TEST_CASE("odd or empty video sizes and bad options are refused", "[video]") {
    const fs::path path = scratch("odd.mp4");
    CHECK_THROWS_WITH(VideoWriter(path, 101, 50),
                      "video size 101x50 is not allowed: width and height must be even and positive");
    CHECK_THROWS_AS(VideoWriter(path, 64, 47), std::invalid_argument);
    CHECK_THROWS_AS(VideoWriter(path, 0, 48), std::invalid_argument);
    CHECK_THROWS_AS(VideoWriter(path, -64, 48), std::invalid_argument);
    VideoOptions options;
    options.codec = "vp9";
    CHECK_THROWS_AS(VideoWriter(path, 64, 48, options), std::invalid_argument);
    options = {};
    options.threads = 0;  // "auto" would make the bytes depend on the machine
    CHECK_THROWS_AS(VideoWriter(path, 64, 48, options), std::invalid_argument);
    options = {};
    options.fps = 0;
    CHECK_THROWS_AS(VideoWriter(path, 64, 48, options), std::invalid_argument);
    CHECK(files_named_like(path) == 0);
}

TEST_CASE("a frame of the wrong size is refused", "[video]") {
    const fs::path path = scratch("wrong_frame.mp4");
    VideoWriter writer(path, kWidth, kHeight);
    CHECK_THROWS_WITH(writer.add(Image(32, 48)), "video frame is 32x48, expected 64x48 RGBA");
    Image short_buffer = moving_bar(0);
    short_buffer.rgba.resize(short_buffer.rgba.size() - 4);
    CHECK_THROWS_AS(writer.add(short_buffer), std::invalid_argument);
    writer.add(moving_bar(0));  // the writer is still usable
    CHECK(writer.frames() == 1);
}

TEST_CASE("a writer destroyed without finish leaves neither the file nor a temporary", "[video]") {
    const fs::path path = scratch("abandoned.mp4");
    {
        VideoWriter writer(path, kWidth, kHeight);
        for (int i = 0; i < 5; ++i) writer.add(moving_bar(i));
        CHECK(files_named_like(path) == 1);  // the temporary, being written
        CHECK_FALSE(fs::exists(path));
    }
    CHECK(files_named_like(path) == 0);
}

TEST_CASE("a video in a missing folder fails naming the path", "[video]") {
    const fs::path path = fs::path(FIGGEN_TEST_ARTIFACT_DIR) / "no-such-folder" / "x.mp4";
    try {
        VideoWriter writer(path, kWidth, kHeight);
        FAIL("no exception");
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        CHECK(what.find(path.string()) != std::string::npos);
        CHECK(what.find("No such file or directory") != std::string::npos);
        CHECK(what.find('\n') == std::string::npos);
    }
    CHECK_FALSE(fs::exists(path.parent_path()));
}

TEST_CASE("a missing video cannot be probed", "[video]") {
    const fs::path path = scratch("missing.mp4");
    CHECK_THROWS_AS(media::probe_video(path), std::runtime_error);
}

TEST_CASE("the same frames with the same options give the same bytes", "[video]") {
    const fs::path a = scratch("same_a.mp4");
    const fs::path b = scratch("same_b.mp4");
    encode_bar(a);
    encode_bar(b);
    const std::string bytes_a = read_bytes(a);
    CHECK(bytes_a.size() > 1000);
    CHECK(bytes_a == read_bytes(b));
    // faststart: the index ("moov") comes before the frames ("mdat").
    CHECK(bytes_a.find("moov") < bytes_a.find("mdat"));
}

TEST_CASE("an unknown x264 preset or tune is refused, naming it and the allowed names", "[video]") {
    const fs::path path = scratch("bad_preset.mp4");
    VideoOptions options;
    options.preset = "quick";
    CHECK_THROWS_WITH(VideoWriter(path, 64, 48, options),
                      "video preset \"quick\" is not allowed: use one of ultrafast, superfast, veryfast, faster, fast, "
                      "medium, slow, slower, veryslow, placebo");
    options = {};
    options.preset = "";  // a preset is required; only the tune may be left out
    CHECK_THROWS_AS(VideoWriter(path, 64, 48, options), std::invalid_argument);
    options = {};
    options.tune = "cartoon";
    CHECK_THROWS_WITH(VideoWriter(path, 64, 48, options),
                      "video tune \"cartoon\" is not allowed: use one of film, animation, grain, stillimage, psnr, ssim, "
                      "fastdecode, zerolatency (or empty for none)");
    CHECK(files_named_like(path) == 0);
}

// libx264 writes its settings into the stream (an SEI user-data message in
// the first frame: "x264 - core ... options: cabac=1 ref=3 ... subme=7 ...").
// The preset's name is not among them, but what it sets is: x264's preset
// table gives medium subme=7 and rc_lookahead=40, veryfast 2 and 10,
// ultrafast subme 0, diamond search, no B-frames, CABAC off; the animation tune raises deblocking to
// 1:1 and the stillimage tune lowers it to -3:-3.
TEST_CASE("the chosen x264 preset and tune are the ones the stream was encoded with", "[video]") {
    struct Case {
        std::string preset, tune;
        std::vector<std::string> options;
    };
    const std::vector<Case> cases = {
        {"medium", "", {"cabac=1", "subme=7", "rc_lookahead=40", "deblock=1:0:0"}},
        {"veryfast", "", {"cabac=1", "subme=2", "rc_lookahead=10", "deblock=1:0:0"}},
        {"ultrafast", "", {"cabac=0", "subme=0", "me=dia", "bframes=0"}},
        {"veryfast", "animation", {"subme=2", "deblock=1:1:1"}},
        {"veryfast", "stillimage", {"subme=2", "deblock=1:-3:-3"}},
    };
    for (const Case& c : cases) {
        INFO("preset " << c.preset << ", tune " << c.tune);
        const fs::path path = scratch("preset_" + c.preset + "_" + c.tune + ".mp4");
        VideoOptions options;
        options.codec = "libx264";
        options.preset = c.preset;
        options.tune = c.tune;
        try {
            encode_bar(path, options);
        } catch (const std::runtime_error& e) {
            WARN("no libx264 in this FFmpeg: " << e.what());
            return;
        }
        const std::string bytes = read_bytes(path);
        const std::size_t sei = bytes.find("x264 - core");
        REQUIRE(sei != std::string::npos);
        const std::string settings = bytes.substr(sei, bytes.find('\0', sei) - sei);
        INFO(settings);
        for (const std::string& o : c.options) CHECK(settings.find(" " + o + " ") != std::string::npos);
    }
}

TEST_CASE("a film from segments encoded apart is the file encoded whole in segments", "[video]") {
    VideoOptions options;
    options.segment_frames = 10;
    const fs::path whole = scratch("whole.mp4"), joined = scratch("joined.mp4");
    encode_bar(whole, options);
    {
        VideoWriter writer(joined, kWidth, kHeight, options);
        for (int first = 0; first < kFrames; first += options.segment_frames) {
            // As another process would: its own encoder, its packets sent as bytes.
            media::VideoSegment segment("segment", kWidth, kHeight, options);
            for (int i = first; i < std::min(kFrames, first + options.segment_frames); ++i) segment.add(moving_bar(i));
            const int frames = segment.frames();
            writer.add_segment(segment.finish(), frames);
        }
        CHECK(writer.frames() == kFrames);
        writer.finish();
    }
    CHECK(read_bytes(joined) == read_bytes(whole));
    const media::VideoInfo info = media::probe_video(joined);
    CHECK(info.frames == kFrames);
    // Each segment starts with a key frame: frames 0, 10 and 20.
    for (int k : {0, 10, 20}) CHECK(std::count(info.key_frames.begin(), info.key_frames.end(), k) == 1);
    // Decoded, every frame still shows its bar where it was drawn.
    for (int i : {0, 9, 10, 24}) {
        const Image frame = media::decode_frame(joined, i);
        CHECK(mean_luma(frame, 2 * i + 2, 2 * i + kBarWidth - 2) > 200);
    }
}

TEST_CASE("a film's preview loops over evenly spread frames of the film scaled to fit", "[video][preview]") {
    const fs::path film = scratch("preview-bar.mp4");
    const fs::path preview = scratch("preview-bar.webp");
    VideoWriter writer(film, kWidth, kHeight);
    for (int i = 0; i < kFrames; ++i) writer.add(moving_bar(i));
    media::PreviewOptions options;
    options.max_width = 32;  // half the film's width: 32 x 24
    options.max_frames = 5;  // frames 0, 6, 12, 18 and 24 of 25
    const media::PreviewInfo written = writer.finish(base::Folder::of(preview), preview.filename().string(), options);
    REQUIRE(fs::exists(film));
    CHECK(media::probe_video(film).frames == kFrames);  // the film is whole

    const media::PreviewInfo read = media::probe_preview(preview);
    CHECK(read.frames == 5);
    CHECK(read.width == 32);
    CHECK(read.height == 24);
    CHECK(read.loop_count == 0);  // for ever
    // As long as the film, 25 frames at 30 fps, in five equal frames: 5 x 166 ms.
    CHECK(read.duration_ms == 5 * 166);
    CHECK(read.bytes == fs::file_size(preview));
    CHECK(written.frames == read.frames);
    CHECK(written.bytes == read.bytes);
    CHECK(written.duration_ms == read.duration_ms);
    // Frame k shows the film's frame 6k: its bar, at x = 2 * 6k in the film,
    // is at x = 6k at half size, 4 pixels wide.
    for (int k = 0; k < 5; ++k) {
        INFO("preview frame " << k);
        const Image frame = media::decode_preview_frame(preview, k);
        REQUIRE(frame.width == 32);
        const int bar = 6 * k;
        CHECK(mean_luma(frame, bar + 1, bar + 3) > 200);                       // the bar, white
        const int away = bar < 16 ? 26 : 2;
        CHECK(mean_luma(frame, away, away + 3) < 120);                        // the background, blue
        CHECK(mean_channel(frame, away, away + 3, 2) > 150);
    }
    CHECK_THROWS_AS(media::decode_preview_frame(preview, 5), std::out_of_range);
    CHECK(files_named_like(preview) == 1);
}

TEST_CASE("a preview too big for its budget is made smaller until it fits", "[video][preview]") {
    // Noise barely compresses: 48 frames of 96 x 96 at quality 70 take far
    // more than the 20 KB allowed here.
    const fs::path film = scratch("preview-noise.mp4");
    const fs::path preview = scratch("preview-noise.webp");
    VideoWriter writer(film, 96, 96);
    std::uint32_t state = 12345;
    for (int i = 0; i < 48; ++i) {
        Image frame(96, 96);
        for (std::size_t p = 0; p < frame.rgba.size(); ++p) {
            state = state * 1664525u + 1013904223u;  // a fixed LCG: the test's own noise
            frame.rgba[p] = (p % 4 == 3) ? 255 : static_cast<std::uint8_t>(state >> 24);
        }
        writer.add(frame);
    }
    media::PreviewOptions options;
    options.max_bytes = 20000;
    const media::PreviewInfo written = writer.finish(base::Folder::of(preview), preview.filename().string(), options);
    CHECK(fs::file_size(preview) <= options.max_bytes);
    CHECK(written.bytes == fs::file_size(preview));
    CHECK(written.quality < options.quality);
    CHECK(media::probe_preview(preview).frames == written.frames);
}

TEST_CASE("a film with a preview leaves neither file when the preview cannot be written", "[video][preview]") {
    const fs::path film = scratch("preview-refused.mp4");
    const fs::path preview = scratch("preview-refused.webp");
    {
        VideoWriter writer(film, kWidth, kHeight);
        for (int i = 0; i < kFrames; ++i) writer.add(moving_bar(i));
        media::PreviewOptions options;
        options.max_bytes = 10;  // no WebP is this small
        CHECK_THROWS_WITH(writer.finish(base::Folder::of(preview), preview.filename().string(), options),
                          Catch::Contains("cannot write") && Catch::Contains("preview-refused.webp"));
        CHECK_FALSE(fs::exists(film));
    }  // the writer gone, its temporary is too
    CHECK_FALSE(fs::exists(preview));
    CHECK(files_named_like(film) == 0);
    CHECK(files_named_like(preview) == 0);
}

TEST_CASE("a film whose last segment is one frame keeps its frame rate and decoding times", "[video][segments]") {
    // 21 frames in segments of 10: the last segment, one frame, has none of
    // x264's B-frame delay; its decoding time follows the others' without a
    // gap, so the MP4's average frame rate is the one it was made with.
    VideoOptions options;
    options.segment_frames = 10;
    options.fps = 5;
    const fs::path path = scratch("short-last-segment.mp4");
    {
        VideoWriter writer(path, kWidth, kHeight, options);
        for (int i = 0; i < 21; ++i) writer.add(moving_bar(i % kFrames));
        writer.finish();
    }
    const media::VideoInfo info = media::probe_video(path);
    CHECK(info.frames == 21);
    CHECK(info.fps == Approx(5.0));
    CHECK(info.duration_seconds == Approx(21 / 5.0));
    CHECK(info.key_frames == std::vector<int>{0, 10, 20});
}
