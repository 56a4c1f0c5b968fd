#pragma once
// The MP4 sink: streams RGBA frames through libswscale and libavcodec into an
// MP4 one frame at a time, so an animation never holds all its frames in
// memory. H.264 (libx264) when FFmpeg has it, MPEG-4 part 2 otherwise.
// The reading side (probe_video, decode_frame) is what the tests check an MP4
// with: decoded frames, never the file's bytes.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/atomic_file.hpp"
#include "render/image.hpp"

namespace media {

using render::any_pixels;
using render::Image;
using render::ImageTooLarge;

struct VideoOptions {
    int fps = 30;  // frames per second, >= 1
    // Encoder threads, pinned to 1: x264's frame threads let its rate
    // control see how far the other frames got, so with 2 the same frames
    // gave other bytes 8 times in 20 on a loaded machine (the test "the same
    // frames with the same options give the same bytes", run 20 times while
    // a build ran; with 1, never). One thread costs speed, not bytes.
    int threads = 1;
    int crf = 18;                // x264 quality 0..51 (lower is better); mpeg4 maps it to a fixed qscale
    std::string codec = "auto";  // "auto" (libx264, else mpeg4), "libx264" or "mpeg4"
    // x264's speed/size trade-off and content tuning (x264_presets() and
    // x264_tunes(); tune "" = none), pinned like the threads: they shape the
    // bytes. mpeg4 ignores both. Chosen by `make bench` (bench/results/encoder.md,
    // this machine, 2 threads): the fastest setting within 0.005 RGB SSIM of
    // medium's and at most 25% larger on both films, measured on a quiet
    // machine (a busy one had picked faster + animation). veryfast +
    // animation: tc7-2 (351 frames, 480 x 520) 0.71 s against medium's
    // 1.34 s, 337 KB against 400, SSIM 0.9309 against 0.9335; bd-500 (251
    // frames, 420 x 640) 0.48 s against 0.75 s, 293 KB against 289, SSIM
    // 0.9535 against 0.9537.
    std::string preset = "veryfast";
    std::string tune = "animation";
    // Frames per segment, each encoded by an encoder of its own (a closed
    // group of pictures from a key frame) and joined by stream copy, so that
    // segments encoded by other processes give the same film; 0: one segment.
    int segment_frames = 0;
    // The container: "mp4", or "webm" (with codec "libvpx-vp9", crf 0..63
    // and libvpx's cpu-used `speed`, see WebmOptions), which the media
    // module writes from a finished MP4 (VideoWriter::finish with a WebM name).
    std::string container = "mp4";
    int speed = 4;
};

// What the film encoders hold and write, measured on figgen's own films
// (the estimates of app/render/formats.cpp add them up).
namespace film_costs {
// x264 (preset medium: 40 frames of look-ahead, 3 B-frames, 3 references,
// each frame with its half-pel planes and its quarter-size copy), over the
// frame canvas. Measured on tc7-1 at 1000 x 1000 with 2, 4, 11, 21, 61 and
// 201 frames: 62, 80, 117, 152, 241 and 244 bytes a pixel above the
// program; at 400 x 400 and 2000 x 2000 (61 frames) 227 and 210 bytes a
// pixel over about 14 MiB of its own.
constexpr double x264_bytes = 16.0 * 1024 * 1024;
constexpr double x264_bytes_per_pixel = 64.0;
constexpr double x264_bytes_per_pixel_frame = 5.0;  // per frame it holds (x264_frames_held)
// The WebM's stage (the MP4 decoded again and encoded as VP9, libvpx
// realtime at cpu-used 6), after x264 has gone. Measured as the peak above
// the same run without it, on tc7-2's film: 37.0 MiB at 480 x 520 and
// 86.5 MiB at 960 x 1040, 21 MiB and 69 bytes a pixel; with a margin, 32
// MiB and 96.
constexpr double vp9_bytes = 32.0 * 1024 * 1024;
constexpr double vp9_bytes_per_pixel = 96.0;
// The most an MP4 or WebM takes a pixel and frame: our films measure 0.002
// to 0.057 (x264 at crf 18), and VP9 at crf 32 takes less than x264 on
// every catalog film.
constexpr double file_bytes_per_pixel_frame = 0.15;
// The frames an x264 encoder holds: its preset's rc-lookahead (x264's
// preset table). medium's 40 is what the constants were measured with;
// veryfast, the films' preset, looks 10 ahead and was measured at 16 MiB
// and 72 to 79 bytes a pixel (tc7-1's film at 2000 x 2000, tc7-2's at
// scale 3), against the 114 this gives.
inline int x264_frames_held(const std::string& preset) {
    static const std::pair<const char*, int> lookahead[] = {
        {"ultrafast", 0}, {"superfast", 0}, {"veryfast", 10}, {"faster", 20},   {"fast", 30},
        {"medium", 40},   {"slow", 50},     {"slower", 60},   {"veryslow", 60}, {"placebo", 60},
    };
    for (const auto& [name, frames] : lookahead)
        if (preset == name) return frames;
    return 60;
}
}  // namespace film_costs

// The film for the web: VP9 (libvpx-vp9) in WebM, made from the MP4 just
// written, decoded back (as the preview is), so that it is the same bytes
// however the MP4 was made. Constant quality (crf, b:v 0), one thread and
// no row multithreading, which keep the bytes the same from run to run, as
// with x264. libvpx's cpu-used `speed`: 0..5 with its "good" deadline, 6..8
// with "realtime". Measured on tc7-2's film (351 frames, 480 x 520, this
// machine): good at 4 took 7.7 s for 219 KB, SSIM 0.9910 against the MP4;
// realtime at 6 1.2 s for 286 KB, SSIM 0.9906; at 8 0.9 s, 328 KB, 0.9898.
struct WebmOptions {
    int crf = 32;  // libvpx-vp9 quality 0..63 (lower is better)
    int speed = 6;
};

// One encoded packet of a film segment; times in frames from the segment's start.
struct VideoPacket {
    std::vector<std::uint8_t> data;
    std::int64_t pts = 0, dts = 0;
    bool key = false;
};

// The names libx264 accepts, fastest preset first.
const std::vector<std::string>& x264_presets();
const std::vector<std::string>& x264_tunes();

// A film's short looping preview: an animated WebP (libwebp) of at most
// max_frames frames spread evenly over the film, first and last included,
// lasting what the film lasts but at most max_seconds, scaled down by area
// averaging to fit max_width x max_height. For a page to show in place of a
// still poster. Kept under max_bytes by lowering the quality, then the
// frames, when a film's frames are too busy.
struct PreviewOptions {
    int max_width = 360, max_height = 360;
    int max_frames = 48;
    double max_seconds = 4.0;
    float quality = 70;                  // libwebp's lossy quality, 0..100
    std::uint64_t max_bytes = 2u << 20;  // 2 MiB
};

// The frames of a film of `film_frames` (>= 1) frames that its preview
// shows: at most options.max_frames, evenly spread, the first and the last
// among them, ascending, none twice.
// Inline: the media module, which links nothing of figgen's, uses it too.
inline std::vector<int> preview_frame_indices(int film_frames, const PreviewOptions& options) {
    if (film_frames < 1 || options.max_frames < 1) throw std::invalid_argument("a preview needs a frame or more");
    const int kept = std::min(options.max_frames, film_frames);
    std::vector<int> wanted;
    for (int k = 0; k < kept; ++k) {
        const int index =
            kept == 1 ? film_frames - 1 : static_cast<int>(std::lround(double(k) * (film_frames - 1) / (kept - 1)));
        if (wanted.empty() || wanted.back() != index) wanted.push_back(index);
    }
    return wanted;
}

struct PreviewInfo {
    int frames = 0;             // frames in the animation
    int width = 0, height = 0;  // pixels
    int loop_count = -1;        // 0: loops for ever
    int duration_ms = 0;        // one loop
    std::uint64_t bytes = 0;    // the file's size
    float quality = 0;          // the quality it was written at
};

// A film's preview made while the film is: its frames (the film's at
// preview_frame_indices(film_frames, options)), decoded back where their
// segments were encoded (VideoSegment::preview_frames), are added in film
// order, each encoded into the animation as it comes.
// VideoWriter::set_preview hands it to the film's writer. Add from one
// thread at a time.
class PreviewAnimation {
public:
    // Throws std::invalid_argument for film_frames or film_fps < 1 or bad
    // options; `shown` is what errors name.
    PreviewAnimation(const std::string& shown, int film_frames, int film_fps, const PreviewOptions& options = {});
    ~PreviewAnimation();
    PreviewAnimation(const PreviewAnimation&) = delete;
    PreviewAnimation& operator=(const PreviewAnimation&) = delete;

    void add(Image frame);  // the next frame; std::logic_error past the last
    bool complete() const { return static_cast<int>(frames_.size()) == wanted_; }
    int film_frames() const { return film_frames_; }
    // Writes the preview of a complete animation to `fd` (VideoWriter).
    PreviewInfo write(int fd, const std::filesystem::path& shown);

private:
    struct Encoder;  // the media module's, kept out of this header
    std::unique_ptr<Encoder> encoder_;
    std::vector<Image> frames_;  // kept for a lower quality, should the preview not fit its budget
    int film_frames_, wanted_;
};

class VideoWriter {
public:
    // Throws std::invalid_argument for an odd or non-positive size or bad
    // options, std::runtime_error (naming the path) when FFmpeg fails.
    // folder/name, written through an exclusive temporary (atomic_file.hpp).
    VideoWriter(const base::Folder& folder, const std::string& name, int width, int height,
                const VideoOptions& options = {});
    VideoWriter(const std::filesystem::path& path, int width, int height, const VideoOptions& options = {});
    ~VideoWriter();  // without finish(), discards the temporary file: no half-written MP4 under the real name
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;
    VideoWriter(VideoWriter&&) noexcept;
    VideoWriter& operator=(VideoWriter&&) noexcept;

    void add(const Image& frame);  // width x height RGBA, rows top-down; else std::invalid_argument
    // The next segment of `frames` frames, encoded elsewhere (VideoSegment)
    // with the same size and options: written as it is (stream copy).
    void add_segment(const std::vector<VideoPacket>& packets, int frames);
    // The preview made beside the film (PreviewAnimation): finish() writes
    // it when the film has the frames it was made for, and decodes the film
    // again for its preview when not.
    void set_preview(std::unique_ptr<PreviewAnimation> preview);
    void finish();  // flushes the encoder, writes the trailer (faststart), renames temp -> final
    // finish(), and also writes folder/name, the film's preview
    // (PreviewOptions), decoded back from the film just written; both
    // files are committed together.
    PreviewInfo finish(const base::Folder& folder, const std::string& name, const PreviewOptions& options = {});
    // The same, also writing folder/webm_name, the film in WebM
    // (WebmOptions), and keeping the MP4 only when `keep_mp4`: a film asked
    // for as WebM alone is encoded to MP4 first and that copy dropped. All
    // the files kept are committed together. Returns the preview's and the
    // WebM's facts.
    struct Copies {
        PreviewInfo preview;
        std::uint64_t webm_bytes = 0;
    };
    Copies finish(const base::Folder& folder, const std::string& preview_name, const PreviewOptions& preview_options,
                  const std::string& webm_name, const WebmOptions& webm_options, bool keep_mp4);

    const std::string& codec_name() const { return codec_name_; }  // "libx264" or "mpeg4"
    int frames() const { return frames_; }                         // frames added so far

private:
    struct Encoder;  // the file and the media module's encoder, kept out of this header
    // The preview on `fd`, preview_ where it is this film's, else decoded from the film.
    PreviewInfo preview_of_film(int fd, const std::filesystem::path& shown, const PreviewOptions& options);
    std::unique_ptr<Encoder> encoder_;
    std::filesystem::path path_;
    int width_ = 0;
    int height_ = 0;
    int fps_ = 0;
    std::string codec_name_;
    int frames_ = 0;
    std::unique_ptr<PreviewAnimation> preview_;
};

// One segment of a film encoded in memory, for a process that makes some
// of a film's segments and sends them to the one that writes it.
class VideoSegment {
public:
    // Throws as VideoWriter for a bad size or options; `shown` is what errors name.
    VideoSegment(const std::string& shown, int width, int height, const VideoOptions& options = {});
    ~VideoSegment();
    VideoSegment(const VideoSegment&) = delete;
    VideoSegment& operator=(const VideoSegment&) = delete;
    void add(const Image& frame);       // as VideoWriter::add
    std::vector<VideoPacket> finish();  // its packets, in decoding order; frees the encoder
    // After finish(): the segment's frames at `indices` (from its start,
    // ascending), decoded back from `packets` (what finish() gave) as the
    // preview decodes the whole film, and fitted to the preview's size.
    std::vector<Image> preview_frames(const std::vector<VideoPacket>& packets, const std::vector<int>& indices,
                                      const PreviewOptions& options = {});
    int frames() const { return frames_; }

private:
    struct Encoder;
    std::unique_ptr<Encoder> encoder_;
    int width_ = 0, height_ = 0, frames_ = 0;
    bool finished_ = false;
};

struct VideoInfo {
    int frames = 0;                 // frames actually decoded, not the container's claim
    int width = 0;                  // pixels
    int height = 0;                 // pixels
    std::string pixel_format;       // FFmpeg's name, e.g. "yuv420p"
    std::string codec;              // FFmpeg's codec name, e.g. "h264" or "mpeg4"
    double duration_seconds = 0.0;  // the video stream's duration
    double fps = 0.0;               // the stream's average frame rate
    std::vector<int> key_frames;    // the frames (display order) decoded as key frames
};

// Opens the file and decodes every frame; throws std::runtime_error naming
// the path when it cannot.
VideoInfo probe_video(const std::filesystem::path& path);

// Reads an animated WebP's size, frames, loop count and duration, and
// decodes its frame `index` (display order) to RGBA; both throw
// std::runtime_error naming the path when they cannot.
PreviewInfo probe_preview(const std::filesystem::path& path);
Image decode_preview_frame(const std::filesystem::path& path, int index);
// folder/name, a smaller copy of the preview source/source_name, a regular
// file there (no symlink followed, no FIFO waited on), for a page such as
// the README: at most options.max_frames of its frames, scaled to fit
// options.max_width x max_height, over the same duration. Only the frames
// kept are held. A canvas whose header claims more than `max_pixels` throws
// ImageTooLarge before anything is decoded.
PreviewInfo write_preview_thumbnail(const base::Folder& source, const std::string& source_name,
                                    const base::Folder& folder, const std::string& name, const PreviewOptions& options,
                                    std::uint64_t max_pixels = any_pixels);
// The canvas size (width, height) of the WebP folder/name as its header
// says, nothing decoded; a regular file there, as above.
PreviewInfo preview_canvas(const base::Folder& folder, const std::string& name);

// Decodes frame `index` (0-based, display order) back to RGBA on `threads`
// decoder threads (0: as many as FFmpeg sees cores; the pixels do not depend
// on it); throws std::out_of_range when the video has fewer frames.
Image decode_frame(const std::filesystem::path& path, int index, int threads = 1);
// The same for folder/name, a regular file there (no symlink followed, no
// FIFO waited on, and libavformat reads the descriptor checked, never the
// path). A film whose header claims frames of more than `max_pixels` pixels
// throws ImageTooLarge before any frame is decoded.
Image decode_frame(const base::Folder& folder, const std::string& name, int index, int threads,
                   std::uint64_t max_pixels);

}  // namespace media
