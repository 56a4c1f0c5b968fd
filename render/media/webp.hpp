#pragma once
// Inside the media module: animated WebP through libwebp (WebPAnimEncoder,
// WebPAnimDecoder), for films' previews.

#include <filesystem>
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
// Every frame of the animated WebP at `path`, and how long one loop lasts.
std::vector<Image> decode_webp(const std::filesystem::path& path, int& duration_ms);
Image decode_webp_frame(const std::filesystem::path& path, int index);

}  // namespace render::media
