#include "media/webp.hpp"

#include <unistd.h>
#include <webp/decode.h>
#include <webp/demux.h>
#include <webp/encode.h>
#include <webp/mux.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace media::codec {
namespace {

struct FreeDecoder {
    void operator()(WebPAnimDecoder* d) const { WebPAnimDecoderDelete(d); }
};
struct FreeData {
    void operator()(WebPData* d) const { WebPDataClear(d); }
};

[[noreturn]] void fail(const std::filesystem::path& shown, const std::string& what) {
    throw std::runtime_error("cannot write " + shown.string() + ": " + what);
}

}  // namespace

AnimationEncoder::AnimationEncoder(const std::filesystem::path& shown, int width, int height, int frame_ms,
                                   float quality)
    : shown_(shown), width_(width), height_(height), frame_ms_(frame_ms) {
    WebPAnimEncoderOptions encoder_options;
    if (!WebPAnimEncoderOptionsInit(&encoder_options)) fail(shown, "libwebp's version does not match its headers");
    encoder_options.anim_params.loop_count = 0;  // for ever
    encoder_options.anim_params.bgcolor = 0xffffffff;
    encoder_.reset(WebPAnimEncoderNew(width, height, &encoder_options));
    if (!encoder_) fail(shown, "creating the WebP encoder");
    config_ = std::make_unique<WebPConfig>();
    if (!WebPConfigInit(config_.get())) fail(shown, "libwebp's version does not match its headers");
    config_->quality = quality;
    config_->method = 2;        // faster than the default 4, files a few per cent larger
    config_->thread_level = 0;  // one thread: the same bytes everywhere
}

AnimationEncoder::~AnimationEncoder() = default;

void AnimationEncoder::add(const Image& frame) {
    if (frame.width != width_ || frame.height != height_) fail(shown_, "its frames differ in size");
    WebPPicture picture;
    if (!WebPPictureInit(&picture)) fail(shown_, "libwebp's version does not match its headers");
    picture.use_argb = 1;
    picture.width = width_;
    picture.height = height_;
    const bool imported = WebPPictureImportRGBA(&picture, frame.rgba.data(), width_ * 4);
    const bool added = imported && WebPAnimEncoderAdd(encoder_.get(), &picture, timestamp_, config_.get());
    WebPPictureFree(&picture);
    if (!added) fail(shown_, std::string("encoding a frame: ") + WebPAnimEncoderGetError(encoder_.get()));
    timestamp_ += frame_ms_;
    ++frames_;
}

std::vector<std::uint8_t> AnimationEncoder::assemble() {
    if (!WebPAnimEncoderAdd(encoder_.get(), nullptr, timestamp_, nullptr))  // the last frame's end
        fail(shown_, std::string("ending the animation: ") + WebPAnimEncoderGetError(encoder_.get()));
    WebPData data;
    WebPDataInit(&data);
    std::unique_ptr<WebPData, FreeData> hold(&data);
    if (!WebPAnimEncoderAssemble(encoder_.get(), &data))
        fail(shown_, std::string("assembling the animation: ") + WebPAnimEncoderGetError(encoder_.get()));
    return {data.bytes, data.bytes + data.size};
}

void AnimationEncoder::FreeEncoder::operator()(WebPAnimEncoder* e) const {
    WebPAnimEncoderDelete(e);
}

int preview_frame_ms(double seconds, std::size_t frames) {
    // Each frame shows for an equal share of the loop, at least 20 ms
    // (what browsers show at the least).
    return std::max(20, static_cast<int>(std::floor(1000.0 * seconds / static_cast<double>(frames))));
}

namespace {

// The animation of `frames` at `quality`, each shown `frame_ms`.
std::vector<std::uint8_t> encode(const std::filesystem::path& shown, const std::vector<const Image*>& frames,
                                 int frame_ms, float quality) {
    AnimationEncoder encoder(shown, frames.front()->width, frames.front()->height, frame_ms, quality);
    for (const Image* frame : frames) encoder.add(*frame);
    return encoder.assemble();
}

void write_all(int fd, const std::filesystem::path& shown, const std::vector<std::uint8_t>& bytes) {
    for (std::size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(shown, std::strerror(errno));
        done += static_cast<std::size_t>(n);
    }
}

std::vector<std::uint8_t> read_all(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path.string() + ": no such file");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The bytes of the file on `fd`, from its start, at most max_webp_bytes.
std::vector<std::uint8_t> read_fd(int fd, const std::filesystem::path& shown) {
    std::vector<std::uint8_t> bytes;
    std::uint8_t chunk[1 << 16];
    for (off_t at = 0;;) {
        const ssize_t n = ::pread(fd, chunk, sizeof chunk, at);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw std::runtime_error("cannot read " + shown.string() + ": " + std::strerror(errno));
        if (n == 0) return bytes;
        if (bytes.size() + static_cast<std::size_t>(n) > max_webp_bytes)
            throw std::runtime_error("cannot read " + shown.string() + ": it holds more than " +
                                     std::to_string(max_webp_bytes >> 20) + " MiB, more than any preview");
        bytes.insert(bytes.end(), chunk, chunk + n);
        at += n;
    }
}

// libwebp's animation decoder over the file's bytes, in RGBA.
class Animation {
public:
    explicit Animation(const std::filesystem::path& path) : Animation(path, read_all(path), any_pixels) {}
    // The bytes of the file `shown`; a canvas of more than `max_pixels` is
    // refused (ImageTooLarge) from its header, before the decoder
    // allocates it.
    Animation(const std::filesystem::path& shown, std::vector<std::uint8_t> bytes, std::uint64_t max_pixels)
        : path_(shown), bytes_(std::move(bytes)) {
        WebPBitstreamFeatures features;
        if (WebPGetFeatures(bytes_.data(), bytes_.size(), &features) != VP8_STATUS_OK)
            fail_read("not a WebP libwebp can read");
        const std::uint64_t width = static_cast<std::uint64_t>(features.width),
                            height = static_cast<std::uint64_t>(features.height);
        if (width * height > max_pixels) throw ImageTooLarge(path_.string(), width, height, max_pixels);
        WebPAnimDecoderOptions options;
        if (!WebPAnimDecoderOptionsInit(&options)) fail_read("libwebp's version does not match its headers");
        options.color_mode = MODE_RGBA;
        options.use_threads = 0;
        const WebPData data{bytes_.data(), bytes_.size()};
        decoder_.reset(WebPAnimDecoderNew(&data, &options));
        if (!decoder_) fail_read("not an animated WebP libwebp can decode");
        if (!WebPAnimDecoderGetInfo(decoder_.get(), &info_)) fail_read("reading its header");
    }

    const WebPAnimInfo& info() const { return info_; }
    std::size_t size() const { return bytes_.size(); }

    // The next frame's pixels (width x height RGBA) and end time, or null after the last.
    const std::uint8_t* next(int& end_ms) {
        if (!WebPAnimDecoderHasMoreFrames(decoder_.get())) return nullptr;
        std::uint8_t* pixels = nullptr;
        if (!WebPAnimDecoderGetNext(decoder_.get(), &pixels, &end_ms)) fail_read("decoding a frame");
        return pixels;
    }

private:
    [[noreturn]] void fail_read(const std::string& what) const {
        throw std::runtime_error("cannot read " + path_.string() + ": " + what);
    }

    std::filesystem::path path_;
    std::vector<std::uint8_t> bytes_;  // the decoder refers to them
    std::unique_ptr<WebPAnimDecoder, FreeDecoder> decoder_;
    WebPAnimInfo info_{};
};

}  // namespace

PreviewInfo write_webp(int fd, const std::filesystem::path& shown, const std::vector<Image>& frames, double seconds,
                       const PreviewOptions& options, std::vector<std::uint8_t> first_try) {
    if (frames.empty()) fail(shown, "a preview needs a frame");
    std::vector<const Image*> kept;
    for (const Image& f : frames) kept.push_back(&f);
    float quality = options.quality;
    std::vector<std::uint8_t> bytes;
    int frame_ms = 0;
    for (;;) {
        frame_ms = preview_frame_ms(seconds, kept.size());
        if (!first_try.empty())
            bytes = std::move(first_try), first_try.clear();
        else
            bytes = encode(shown, kept, frame_ms, quality);
        if (bytes.size() <= options.max_bytes) break;
        if (quality > 10) {
            // Lossy WebP's size falls about in proportion with the quality
            // here: aim a tenth under the budget, and go down at least 10.
            const float aimed = quality * 0.9f * float(options.max_bytes) / float(bytes.size());
            quality = std::max(10.0f, std::min(quality - 10, aimed));
        } else if (kept.size() > 2) {
            std::vector<const Image*> half;  // every other frame, the last kept
            for (std::size_t i = 0; i < kept.size(); i += 2) half.push_back(kept[i]);
            if (half.back() != kept.back()) half.push_back(kept.back());
            kept = std::move(half);
        } else {
            fail(shown, "its frames do not fit " + std::to_string(options.max_bytes) + " bytes");
        }
    }
    write_all(fd, shown, bytes);
    PreviewInfo info;
    info.frames = static_cast<int>(kept.size());
    info.width = frames.front().width;
    info.height = frames.front().height;
    info.loop_count = 0;
    info.duration_ms = info.frames * frame_ms;
    info.bytes = bytes.size();
    info.quality = quality;
    return info;
}

PreviewInfo probe_webp(const std::filesystem::path& path) {
    Animation animation(path);
    PreviewInfo info;
    info.width = static_cast<int>(animation.info().canvas_width);
    info.height = static_cast<int>(animation.info().canvas_height);
    info.loop_count = static_cast<int>(animation.info().loop_count);
    info.bytes = animation.size();
    int end_ms = 0;
    while (animation.next(end_ms)) ++info.frames;  // decoded, not the header's claim
    info.duration_ms = end_ms;
    return info;
}

std::vector<Image> decode_webp_frames(int fd, const std::filesystem::path& shown, std::uint64_t max_pixels,
                                      int max_frames, const std::function<Image(const Image&)>& keep,
                                      int& duration_ms) {
    Animation animation(shown, read_fd(fd, shown), max_pixels);
    const int total = static_cast<int>(animation.info().frame_count);
    if (total < 1) throw std::runtime_error("cannot read " + shown.string() + ": it has no frames");
    const int kept = std::min(std::max(1, max_frames), total);
    std::vector<int> wanted;  // in order; a short animation repeats no frame
    for (int k = 0; k < kept; ++k) {
        const int index = kept == 1 ? total - 1 : static_cast<int>(std::lround(double(k) * (total - 1) / (kept - 1)));
        if (wanted.empty() || wanted.back() != index) wanted.push_back(index);
    }
    Image canvas(static_cast<int>(animation.info().canvas_width), static_cast<int>(animation.info().canvas_height));
    std::vector<Image> frames;
    std::size_t next = 0;
    for (int i = 0; const std::uint8_t* pixels = animation.next(duration_ms); ++i) {
        if (next < wanted.size() && wanted[next] == i) {
            std::memcpy(canvas.rgba.data(), pixels, canvas.rgba.size());
            frames.push_back(keep(canvas));
            ++next;
        }
    }
    if (frames.empty()) throw std::runtime_error("cannot read " + shown.string() + ": it has no frames");
    return frames;
}

PreviewInfo webp_canvas(int fd, const std::filesystem::path& shown) {
    // The RIFF header and the first chunk (VP8X for an animation, VP8 or
    // VP8L for a still) are all WebPGetFeatures needs.
    std::uint8_t head[64];
    ssize_t n = 0;
    do n = ::pread(fd, head, sizeof head, 0);
    while (n < 0 && errno == EINTR);
    if (n < 0) throw std::runtime_error("cannot read " + shown.string() + ": " + std::strerror(errno));
    WebPBitstreamFeatures features;
    const VP8StatusCode status = WebPGetFeatures(head, static_cast<std::size_t>(n), &features);
    if (status != VP8_STATUS_OK || features.width < 1 || features.height < 1)
        throw std::runtime_error("cannot read " + shown.string() + ": not a WebP libwebp can read");
    PreviewInfo info;
    info.width = features.width;
    info.height = features.height;
    return info;
}

Image decode_webp_frame(const std::filesystem::path& path, int index) {
    Animation animation(path);
    int end_ms = 0;
    for (int i = 0;; ++i) {
        const std::uint8_t* pixels = animation.next(end_ms);
        if (!pixels)
            throw std::out_of_range(path.string() + " has " + std::to_string(i) + " frames, no frame " +
                                    std::to_string(index));
        if (i == index) {
            Image image(static_cast<int>(animation.info().canvas_width),
                        static_cast<int>(animation.info().canvas_height));
            std::memcpy(image.rgba.data(), pixels, image.rgba.size());
            return image;
        }
    }
}

}  // namespace media::codec
