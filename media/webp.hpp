#pragma once
// Inside the media module: animated WebP through libwebp (WebPAnimEncoder,
// WebPAnimDecoder), for films' previews.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "render/image.hpp"
#include "media/video.hpp"

struct WebPAnimEncoder;
struct WebPConfig;

namespace media::codec {

// libwebp's animation encoder (WebPAnimEncoder, lossy at `quality`, one
// thread), fed one frame at a time, each shown `frame_ms`; loops for ever.
// Errors name `shown`.
class AnimationEncoder {
public:
    AnimationEncoder(const std::filesystem::path& shown, int width, int height, int frame_ms, float quality);
    ~AnimationEncoder();
    AnimationEncoder(const AnimationEncoder&) = delete;
    AnimationEncoder& operator=(const AnimationEncoder&) = delete;
    void add(const Image& frame);          // width x height RGBA
    std::vector<std::uint8_t> assemble();  // the file's bytes, once every frame is added
    int frames() const { return frames_; }

private:
    struct FreeEncoder {
        void operator()(WebPAnimEncoder* e) const;
    };
    std::filesystem::path shown_;
    int width_, height_, frame_ms_, timestamp_ = 0, frames_ = 0;
    std::unique_ptr<WebPAnimEncoder, FreeEncoder> encoder_;
    std::unique_ptr<WebPConfig> config_;
};

// How long each of `frames` frames shows in a preview lasting `seconds`.
int preview_frame_ms(double seconds, std::size_t frames);

// Writes `frames` (RGBA, all one size) to `fd` as an animated WebP that
// loops for ever and lasts `seconds`, at options.quality, or lower, then
// with every other frame, until it fits options.max_bytes. `first_try`,
// if given, is the AnimationEncoder's bytes of all the frames at
// options.quality (encoded as they came). Errors name `shown`.
PreviewInfo write_webp(int fd, const std::filesystem::path& shown, const std::vector<Image>& frames, double seconds,
                       const PreviewOptions& options, std::vector<std::uint8_t> first_try = {});
PreviewInfo probe_webp(const std::filesystem::path& path);
Image decode_webp_frame(const std::filesystem::path& path, int index);

// At most `max_frames` frames of the animated WebP on `fd` (read from its
// start, never closed here), evenly spread, first and last included, each
// passed through `keep` as it is decoded (so only what `keep` returns is
// held), and how long one loop lasts. A canvas whose header claims more
// than `max_pixels` throws ImageTooLarge before the decoder is made; a file
// over max_webp_bytes is refused. Errors name `shown`.
std::vector<Image> decode_webp_frames(int fd, const std::filesystem::path& shown, std::uint64_t max_pixels,
                                      int max_frames, const std::function<Image(const Image&)>& keep, int& duration_ms);
// The canvas size of the WebP on `fd` as its header says (libwebp's
// WebPGetFeatures on the file's first bytes; nothing decoded): width and
// height in a PreviewInfo, frames left 0.
PreviewInfo webp_canvas(int fd, const std::filesystem::path& shown);

// The largest WebP read: figgen's previews are at most 2 MiB.
constexpr std::size_t max_webp_bytes = 64u << 20;

}  // namespace media::codec
