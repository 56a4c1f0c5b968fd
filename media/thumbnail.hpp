#pragma once
// Small copies of figures for the gallery and the README, scaled by
// FFmpeg's libswscale with area averaging (every source pixel counts, as a
// downscale should), in RGBA throughout.

#include "render/image.hpp"

namespace media {

using render::Image;

// `image` scaled to fit `max_width` x `max_height`, keeping its aspect ratio
// (each side at least 1); an image already inside is returned as it is.
// Throws std::invalid_argument for an empty image or a size below 1.
Image thumbnail(const Image& image, int max_width, int max_height);

}  // namespace media
