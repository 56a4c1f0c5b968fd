#include "media/video.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "base/atomic_file.hpp"
#include "media/media.hpp"

// The arguments are checked here; FFmpeg's work is done by the media module
// (media/media.hpp), opened on first use.

namespace media {

// The file, and the module's encoder writing into it.
struct VideoWriter::Encoder {
    Encoder(const base::Folder& folder, const std::string& name) : file(folder, name) {}

    // Declared first so it is destroyed last: the encoder closes its I/O
    // before the temporary is removed.
    base::AtomicFile file;
    std::unique_ptr<codec::Encoder> media;
    bool finished = false;
};

namespace {

// Checked here rather than left to libx264, which would refuse an unknown
// name only as "opening the encoder: Invalid argument".
void check_name(const char* what, const std::string& name, const std::vector<std::string>& allowed, bool may_be_empty) {
    if (may_be_empty && name.empty()) return;
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) return;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw std::invalid_argument(std::string(what) + " \"" + name + "\" is not allowed: use one of " + list +
                                (may_be_empty ? " (or empty for none)" : ""));
}

void validate(int width, int height, const VideoOptions& options) {
    if (width <= 0 || height <= 0 || width % 2 != 0 || height % 2 != 0)
        throw std::invalid_argument("video size " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is not allowed: width and height must be even and positive");
    if (options.fps < 1) throw std::invalid_argument("video fps must be at least 1");
    // 0 would mean "as many as there are cores", and the bytes would differ by machine.
    if (options.threads < 1) throw std::invalid_argument("video threads must be at least 1");
    if (options.crf < 0 || options.crf > 51) throw std::invalid_argument("video crf must be in 0..51");
    check_name("video preset", options.preset, x264_presets(), false);
    check_name("video tune", options.tune, x264_tunes(), true);
    if (options.segment_frames < 0) throw std::invalid_argument("video segment frames must not be negative");
}

void check_frame(const Image& frame, int width, int height) {
    if (frame.width != width || frame.height != height ||
        frame.rgba.size() != static_cast<std::size_t>(width) * height * 4)
        throw std::invalid_argument("video frame is " + std::to_string(frame.width) + "x" +
                                    std::to_string(frame.height) + ", expected " + std::to_string(width) + "x" +
                                    std::to_string(height) + " RGBA");
}

// A file read by the media module: folder/name opened here, a regular file
// (open_regular_at), and handed over as its descriptor.
struct ReadOnly {
    ReadOnly(const base::Folder& folder, const std::string& name)
        : shown(folder / name), fd(base::open_regular_at(folder, name)) {
        if (fd < 0) throw std::runtime_error("cannot read " + shown.string() + ": " + base::not_opened_reason(errno));
    }
    ~ReadOnly() { ::close(fd); }
    ReadOnly(const ReadOnly&) = delete;
    ReadOnly& operator=(const ReadOnly&) = delete;
    std::filesystem::path shown;
    int fd;
};

void check_preview(const PreviewOptions& options) {
    if (options.max_width < 1 || options.max_height < 1 || options.max_frames < 1 || !(options.max_seconds > 0) ||
        !(options.quality >= 0 && options.quality <= 100) || options.max_bytes < 1)
        throw std::invalid_argument("preview options out of range");
}

}  // namespace

// As x264.h's x264_preset_names and x264_tune_names (x264 0.164).
const std::vector<std::string>& x264_presets() {
    static const std::vector<std::string> names = {"ultrafast", "superfast", "veryfast", "faster",   "fast",
                                                   "medium",    "slow",      "slower",   "veryslow", "placebo"};
    return names;
}

const std::vector<std::string>& x264_tunes() {
    static const std::vector<std::string> names = {"film", "animation", "grain",      "stillimage",
                                                   "psnr", "ssim",      "fastdecode", "zerolatency"};
    return names;
}

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, const VideoOptions& options)
    : VideoWriter(base::Folder::of(path), path.filename().string(), width, height, options) {}

VideoWriter::VideoWriter(const base::Folder& folder, const std::string& name, int width, int height,
                         const VideoOptions& options)
    : path_(folder / name), width_(width), height_(height), fps_(options.fps) {
    validate(width, height, options);
    const codec::Api& media = codec::api();
    auto e = std::make_unique<Encoder>(folder, name);
    e->media = media.open_encoder(e->file.fd(), path_, width, height, options);
    codec_name_ = e->media->codec_name();
    encoder_ = std::move(e);
}

VideoWriter::~VideoWriter() = default;  // the encoder closes its I/O, then AtomicFile removes the temporary
VideoWriter::VideoWriter(VideoWriter&&) noexcept = default;
VideoWriter& VideoWriter::operator=(VideoWriter&&) noexcept = default;

void VideoWriter::add(const Image& frame) {
    if (!encoder_ || encoder_->finished) throw std::logic_error("VideoWriter::add after finish()");
    check_frame(frame, width_, height_);
    encoder_->media->add(frame);
    ++frames_;
}

void VideoWriter::add_segment(const std::vector<VideoPacket>& packets, int frames) {
    if (!encoder_ || encoder_->finished) throw std::logic_error("VideoWriter::add_segment after finish()");
    if (frames < 0) throw std::invalid_argument("a video segment of " + std::to_string(frames) + " frames");
    encoder_->media->add_segment(packets, frames);
    frames_ += frames;
}

PreviewInfo VideoWriter::preview_of_film(int fd, const std::filesystem::path& shown, const PreviewOptions& options) {
    // Made beside the film, if it is this film's: the same pixels as
    // decoding the film here.
    if (preview_ && preview_->film_frames() == frames_ && preview_->complete()) return preview_->write(fd, shown);
    return codec::api().write_preview(fd, shown, encoder_->file.fd(), frames_, fps_, options);
}

void VideoWriter::set_preview(std::unique_ptr<PreviewAnimation> preview) {
    if (!encoder_ || encoder_->finished) throw std::logic_error("VideoWriter::set_preview after finish()");
    preview_ = std::move(preview);
}

struct PreviewAnimation::Encoder {
    std::unique_ptr<codec::PreviewEncoder> media;
};

PreviewAnimation::PreviewAnimation(const std::string& shown, int film_frames, int film_fps,
                                   const PreviewOptions& options)
    : film_frames_(film_frames) {
    check_preview(options);
    if (film_frames < 1 || film_fps < 1)
        throw std::invalid_argument("a preview needs a film of a frame or more at a frame a second or more");
    wanted_ = static_cast<int>(preview_frame_indices(film_frames, options).size());
    encoder_ = std::make_unique<Encoder>();
    encoder_->media = codec::api().open_preview(shown, film_frames, film_fps, options);
}

PreviewAnimation::~PreviewAnimation() = default;

void PreviewAnimation::add(Image frame) {
    if (complete()) throw std::logic_error("PreviewAnimation::add past its last frame");
    encoder_->media->add(frame);
    frames_.push_back(std::move(frame));
}

PreviewInfo PreviewAnimation::write(int fd, const std::filesystem::path& shown) {
    if (!complete()) throw std::logic_error("PreviewAnimation::write before its last frame");
    return encoder_->media->write(fd, shown, frames_);
}

struct VideoSegment::Encoder {
    std::unique_ptr<codec::SegmentEncoder> media;
};

VideoSegment::VideoSegment(const std::string& shown, int width, int height, const VideoOptions& options)
    : width_(width), height_(height) {
    validate(width, height, options);
    encoder_ = std::make_unique<Encoder>();
    encoder_->media = codec::api().open_segment(shown, width, height, options);
}

VideoSegment::~VideoSegment() = default;

void VideoSegment::add(const Image& frame) {
    if (finished_) throw std::logic_error("VideoSegment::add after finish()");
    check_frame(frame, width_, height_);
    encoder_->media->add(frame);
    ++frames_;
}

std::vector<VideoPacket> VideoSegment::finish() {
    if (finished_) throw std::logic_error("VideoSegment::finish called twice");
    finished_ = true;
    return encoder_->media->finish();
}

std::vector<Image> VideoSegment::preview_frames(const std::vector<VideoPacket>& packets,
                                                const std::vector<int>& indices, const PreviewOptions& options) {
    if (!finished_) throw std::logic_error("VideoSegment::preview_frames before finish()");
    check_preview(options);
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] < 0 || indices[i] >= frames_ || (i > 0 && indices[i] <= indices[i - 1]))
            throw std::invalid_argument("VideoSegment::preview_frames: frame indices must ascend within the segment");
    return encoder_->media->preview_frames(packets, indices, options);
}

void VideoWriter::finish() {
    if (!encoder_ || encoder_->finished) throw std::logic_error("VideoWriter::finish called twice");
    if (frames_ == 0) throw std::logic_error("cannot write " + path_.string() + ": no frames were added");
    encoder_->media->finish();
    encoder_->file.commit();
    encoder_->finished = true;
}

PreviewInfo VideoWriter::finish(const base::Folder& folder, const std::string& name, const PreviewOptions& options) {
    if (!encoder_ || encoder_->finished) throw std::logic_error("VideoWriter::finish called twice");
    if (frames_ == 0) throw std::logic_error("cannot write " + path_.string() + ": no frames were added");
    check_preview(options);
    encoder_->media->finish();
    base::AtomicFile preview(folder, name);
    const PreviewInfo info = preview_of_film(preview.fd(), folder / name, options);
    encoder_->file.commit();
    preview.commit();
    encoder_->finished = true;
    return info;
}

VideoWriter::Copies VideoWriter::finish(const base::Folder& folder, const std::string& preview_name,
                                        const PreviewOptions& preview_options, const std::string& webm_name,
                                        const WebmOptions& webm_options, bool keep_mp4) {
    if (!encoder_ || encoder_->finished) throw std::logic_error("VideoWriter::finish called twice");
    if (frames_ == 0) throw std::logic_error("cannot write " + path_.string() + ": no frames were added");
    check_preview(preview_options);
    if (webm_options.crf < 0 || webm_options.crf > 63 || webm_options.speed < 0 || webm_options.speed > 8)
        throw std::invalid_argument("WebM options out of range: crf 0..63, speed 0..8");
    encoder_->media->finish();
    Copies copies;
    base::AtomicFile preview(folder, preview_name);
    copies.preview = preview_of_film(preview.fd(), folder / preview_name, preview_options);
    std::optional<base::AtomicFile> webm;
    if (!webm_name.empty()) {
        webm.emplace(folder, webm_name);
        copies.webm_bytes =
            codec::api().write_webm(webm->fd(), folder / webm_name, encoder_->file.fd(), fps_, webm_options);
    }
    if (keep_mp4) encoder_->file.commit();  // else the temporary MP4 goes with the writer
    preview.commit();
    if (webm) webm->commit();
    encoder_->finished = true;
    return copies;
}

PreviewInfo probe_preview(const std::filesystem::path& path) {
    return codec::api().probe_preview(path);
}

Image decode_preview_frame(const std::filesystem::path& path, int index) {
    if (index < 0) throw std::out_of_range("preview frame index " + std::to_string(index) + " is negative");
    return codec::api().decode_preview_frame(path, index);
}

PreviewInfo write_preview_thumbnail(const base::Folder& source, const std::string& source_name,
                                    const base::Folder& folder, const std::string& name, const PreviewOptions& options,
                                    std::uint64_t max_pixels) {
    check_preview(options);
    const ReadOnly in(source, source_name);
    base::AtomicFile file(folder, name);
    const PreviewInfo info =
        codec::api().write_preview_thumbnail(file.fd(), folder / name, in.fd, in.shown, max_pixels, options);
    file.commit();
    return info;
}

PreviewInfo preview_canvas(const base::Folder& folder, const std::string& name) {
    const ReadOnly in(folder, name);
    return codec::api().webp_canvas(in.fd, in.shown);
}

VideoInfo probe_video(const std::filesystem::path& path) {
    return codec::api().probe_video(path);
}

Image decode_frame(const std::filesystem::path& path, int index, int threads) {
    if (index < 0) throw std::out_of_range("video frame index " + std::to_string(index) + " is negative");
    if (threads < 0) throw std::invalid_argument("decoder threads " + std::to_string(threads) + " is negative");
    return codec::api().decode_frame(path, index, threads);
}

Image decode_frame(const base::Folder& folder, const std::string& name, int index, int threads,
                   std::uint64_t max_pixels) {
    if (index < 0) throw std::out_of_range("video frame index " + std::to_string(index) + " is negative");
    if (threads < 0) throw std::invalid_argument("decoder threads " + std::to_string(threads) + " is negative");
    const ReadOnly in(folder, name);
    return codec::api().decode_film_frame(in.fd, in.shown, index, threads, max_pixels);
}

}  // namespace media
