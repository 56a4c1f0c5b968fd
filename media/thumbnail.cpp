#include "media/thumbnail.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "media/media.hpp"

namespace media {

Image thumbnail(const Image& image, int max_width, int max_height) {
    if (image.width < 1 || image.height < 1 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw std::invalid_argument("thumbnail: the image is empty or its pixel buffer has the wrong size");
    if (max_width < 1 || max_height < 1)
        throw std::invalid_argument("thumbnail: the largest size must be at least 1 x 1");
    const double factor = std::min({1.0, double(max_width) / image.width, double(max_height) / image.height});
    if (factor == 1.0) return image;
    const int width = std::max(1, int(std::lround(image.width * factor)));
    const int height = std::max(1, int(std::lround(image.height * factor)));
    return codec::api().scale(image, width, height);
}

}  // namespace media
