#pragma once
// Inside the media module: animated WebP through libwebp (WebPAnimEncoder,
// WebPAnimDecoder), for films' previews.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "render/image.hpp"
#include "render/video.hpp"

namespace render::media {

// Writes `frames` (RGBA, all one size) to `fd` as an animated WebP that
// loops for ever and lasts `seconds`, at options.quality, or lower, then
// with every other frame, until it fits options.max_bytes. Errors name
// `shown`.
PreviewInfo write_webp(int fd, const std::filesystem::path& shown, const std::vector<Image>& frames, double seconds,
                       const PreviewOptions& options);
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

}  // namespace render::media
