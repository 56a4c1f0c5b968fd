#pragma once
// Image-checksum tests. A rendered image is checked first by the SHA-256 of
// its decoded RGBA pixels against tests/golden/<name>.sha256 (recorded with
// the GL_RENDERER and GL_VERSION that made it). When the hash differs (another
// Mesa, another LLVM), it is compared with tests/golden/<name>.png: a pixel
// differs when any channel is off by more than 3, and at most 0.1% of pixels
// may differ. Beyond that the test fails and the actual image and a diff image
// are written to the test artifact folder.

#include <filesystem>
#include <string>

#include "render/image.hpp"

namespace testkit {

std::string pixel_hash(const render::Image& image);

struct GoldenCheck {
    bool hash_matched = false;     // identical pixels
    bool within_tolerance = false; // passes (identical, or close enough)
    long differing_pixels = 0;     // pixels with a channel delta > max_delta
    int largest_delta = 0;         // over all channels and pixels
    std::string message;           // one line for the test log
    std::string recorded_renderer; // the golden's GL_RENDERER, a newline, its GL_VERSION
};

inline constexpr int max_delta = 3;
inline constexpr double max_differing_fraction = 0.001;

// `renderer` is the GL_RENDERER that drew `actual`, for the message.
GoldenCheck check_golden(const std::string& name, const render::Image& actual, const std::string& renderer);

// Writes <dir>/<name>.png and <name>.sha256 (hash, `renderer` and
// `version`, the GL_RENDERER and GL_VERSION that drew it).
void write_golden(const std::filesystem::path& dir, const std::string& name, const render::Image& image,
                  const std::string& renderer, const std::string& version);

}  // namespace testkit
