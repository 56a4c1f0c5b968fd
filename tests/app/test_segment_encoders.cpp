// A film's segments encoded side by side (app/render/segment_encoders.hpp): the
// MP4 is the same bytes with any number of workers, on a busy machine too,
// and a worker's failure reaches the caller.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "app/render/segment_encoders.hpp"
#include "figgen_run.hpp"
#include "media/video.hpp"

namespace fs = std::filesystem;
using render::Image;

namespace {

constexpr int width = 96, height = 64, frames = 37;

// Frame i: a disc moving across a gradient, different in every frame.
Image frame(int i) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            const int dx = x - (10 + 2 * i), dy = y - 32;
            const bool disc = dx * dx + dy * dy < 100;
            p[0] = disc ? 250 : static_cast<std::uint8_t>(2 * x);
            p[1] = disc ? 200 : static_cast<std::uint8_t>(3 * y);
            p[2] = static_cast<std::uint8_t>((x + y + 5 * i) & 255);
            p[3] = 255;
        }
    return image;
}

media::VideoOptions options() {
    media::VideoOptions o;
    o.segment_frames = 5;  // 8 segments, the last of 2 frames
    return o;
}

fs::path scratch(const std::string& name) {
    static const fs::path dir = testkit::fresh_dir("segment-encoders");  // made once a process
    return dir / name;
}

// The film encoded by `workers` side by side.
std::string side_by_side(const fs::path& path, int workers) {
    media::VideoWriter writer(path, width, height, options());
    app::SegmentEncoders encoders(writer, path.string(), width, height, options(), workers);
    for (int i = 0; i < frames; ++i) encoders.add(frame(i));
    encoders.finish();
    CHECK(writer.frames() == frames);
    writer.finish();
    return testkit::slurp(path);
}

}  // namespace

TEST_CASE("segments encoded side by side give the film encoded one segment after another", "[video][segments]") {
    const fs::path whole = scratch("whole.mp4");
    {
        media::VideoWriter writer(whole, width, height, options());
        for (int i = 0; i < frames; ++i) writer.add(frame(i));
        writer.finish();
    }
    const std::string expected = testkit::slurp(whole);
    REQUIRE(expected.size() > 1000);
    for (int workers : {1, 2, 3, 8, 20}) {
        INFO(workers << " workers");
        CHECK(side_by_side(scratch("w" + std::to_string(workers) + ".mp4"), workers) == expected);
    }
    // And beside a CPU hog on every core, five times over: timing changes
    // which segment finishes first, never the bytes.
    const testkit::CpuHog hog(static_cast<int>(std::max(2u, std::thread::hardware_concurrency())));
    for (int run = 0; run < 5; ++run) {
        INFO("run " << run << " beside a CPU hog");
        CHECK(side_by_side(scratch("hog" + std::to_string(run) + ".mp4"), 4) == expected);
    }
    const media::VideoInfo info = media::probe_video(whole);
    CHECK(info.frames == frames);
    CHECK(info.key_frames == std::vector<int>{0, 5, 10, 15, 20, 25, 30, 35});
}

TEST_CASE("a segment's failure reaches the caller and no film is written", "[video][segments]") {
    const fs::path path = scratch("failed.mp4");
    {
        media::VideoWriter writer(path, width, height, options());
        app::SegmentEncoders encoders(writer, path.string(), width, height, options(), 3);
        encoders.add(frame(0));
        encoders.add(Image(width + 2, height));  // a frame of the wrong size: its worker throws
        bool thrown = false;
        try {
            for (int i = 2; i < frames; ++i) encoders.add(frame(i));
            encoders.finish();
        } catch (const std::invalid_argument& e) {
            thrown = true;
            CHECK_THAT(e.what(), Catch::Contains("video frame is 98x64, expected 96x64"));
        }
        CHECK(thrown);
    }  // the writer is dropped unfinished
    CHECK_FALSE(fs::exists(path));
}

TEST_CASE("segment encoders dropped without finish stop their workers", "[video][segments]") {
    const fs::path path = scratch("dropped.mp4");
    {
        media::VideoWriter writer(path, width, height, options());
        app::SegmentEncoders encoders(writer, path.string(), width, height, options(), 4);
        for (int i = 0; i < 17; ++i) encoders.add(frame(i));
    }
    CHECK_FALSE(fs::exists(path));
}

TEST_CASE("segment encoders need segments and a worker", "[video][segments]") {
    const fs::path path = scratch("refused.mp4");
    media::VideoWriter writer(path, width, height, options());
    CHECK_THROWS_AS(app::SegmentEncoders(writer, "x", width, height, media::VideoOptions{}, 2), std::invalid_argument);
    CHECK_THROWS_AS(app::SegmentEncoders(writer, "x", width, height, options(), 0), std::invalid_argument);
}

namespace {

// The film (as side_by_side) with its preview, made beside the film by
// workers planned for `planned` frames (0: none planned), of which `given`
// come; returns the preview's bytes.
std::string preview_beside(const fs::path& dir, int workers, int planned, int given,
                           const media::PreviewOptions& preview) {
    fs::create_directories(dir);
    media::VideoWriter writer(dir / "film.mp4", width, height, options());
    app::SegmentEncoders encoders(writer, (dir / "film.mp4").string(), width, height, options(), workers, planned,
                                  preview);
    for (int i = 0; i < given; ++i) encoders.add(frame(i));
    encoders.finish();
    writer.finish(base::Folder::of(dir / "x"), "film.webp", preview);
    return testkit::slurp(dir / "film.webp");
}

// The same film's preview decoded from the finished MP4, one encoder.
std::string preview_after(const fs::path& dir, int given, const media::PreviewOptions& preview) {
    fs::create_directories(dir);
    media::VideoWriter writer(dir / "film.mp4", width, height, options());
    for (int i = 0; i < given; ++i) writer.add(frame(i));
    writer.finish(base::Folder::of(dir / "x"), "film.webp", preview);
    return testkit::slurp(dir / "film.webp");
}

}  // namespace

TEST_CASE("a preview made beside the film is the preview decoded from it", "[video][segments][preview]") {
    media::PreviewOptions few;  // fewer frames than the film, spread over its segments
    few.max_frames = 9;
    media::PreviewOptions all;  // every frame
    all.max_frames = 48;
    media::PreviewOptions tight = few;  // over its budget: a lower quality, as write_webp's loop gives
    tight.max_bytes = 3000;
    int n = 0;
    for (const media::PreviewOptions& preview : {few, all, tight}) {
        const std::string expected = preview_after(scratch("after" + std::to_string(n)), frames, preview);
        REQUIRE(expected.size() > 100);
        for (int workers : {2, 3, 8}) {
            INFO("options " << n << ", " << workers << " workers");
            CHECK(preview_beside(scratch("beside" + std::to_string(n) + "-" + std::to_string(workers)), workers, frames,
                                 frames, preview) == expected);
        }
        ++n;
    }
    // The budget was what made the tight one smaller.
    CHECK(media::probe_preview(scratch("after2") / "film.webp").bytes <= 3000);
    CHECK(media::probe_preview(scratch("after0") / "film.webp").bytes > 3000);

    // A film that ends before its planned end (a model at a fixed point):
    // its preview is decoded from it as before, not made of the planned frames.
    const std::string short_film = preview_after(scratch("short-after"), 23, few);
    CHECK(preview_beside(scratch("short-beside"), 3, frames, 23, few) == short_film);
    CHECK(media::probe_preview(scratch("short-beside") / "film.webp").frames == 9);
}

TEST_CASE("a preview animation takes its frames in order, and no more", "[video][preview]") {
    media::PreviewOptions preview;
    preview.max_frames = 3;
    CHECK(media::preview_frame_indices(37, preview) == std::vector<int>{0, 18, 36});
    CHECK(media::preview_frame_indices(2, preview) == std::vector<int>{0, 1});
    CHECK(media::preview_frame_indices(1, preview) == std::vector<int>{0});
    CHECK_THROWS_AS(media::preview_frame_indices(0, preview), std::invalid_argument);
    CHECK_THROWS_AS(media::PreviewAnimation("x", 0, 30, preview), std::invalid_argument);
    CHECK_THROWS_AS(media::PreviewAnimation("x", 10, 0, preview), std::invalid_argument);

    media::PreviewAnimation animation("x.webp", 37, 30, preview);
    CHECK_FALSE(animation.complete());
    CHECK_THROWS_AS(animation.write(-1, "x.webp"), std::logic_error);  // before its last frame
    for (int i : {0, 18, 36}) animation.add(frame(i));
    CHECK(animation.complete());
    CHECK_THROWS_AS(animation.add(frame(1)), std::logic_error);
}
