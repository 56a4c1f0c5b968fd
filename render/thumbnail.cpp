#include "render/thumbnail.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

extern "C" {
#include <libswscale/swscale.h>
}

namespace render {

Image thumbnail(const Image& image, int max_width, int max_height) {
    if (image.width < 1 || image.height < 1 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw std::invalid_argument("thumbnail: the image is empty or its pixel buffer has the wrong size");
    if (max_width < 1 || max_height < 1)
        throw std::invalid_argument("thumbnail: the largest size must be at least 1 x 1");
    const double factor = std::min({1.0, double(max_width) / image.width, double(max_height) / image.height});
    if (factor == 1.0) return image;
    const int width = std::max(1, int(std::lround(image.width * factor)));
    const int height = std::max(1, int(std::lround(image.height * factor)));
    std::unique_ptr<SwsContext, void (*)(SwsContext*)> scaler(
        sws_getContext(image.width, image.height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_RGBA,
                       SWS_AREA | SWS_ACCURATE_RND, nullptr, nullptr, nullptr),
        sws_freeContext);
    if (!scaler) throw std::runtime_error("thumbnail: libswscale cannot scale RGBA");
    Image out(width, height);
    const std::uint8_t* source[] = {image.rgba.data()};
    const int source_stride[] = {image.width * 4};
    std::uint8_t* target[] = {out.rgba.data()};
    const int target_stride[] = {width * 4};
    if (sws_scale(scaler.get(), source, source_stride, 0, image.height, target, target_stride) != height)
        throw std::runtime_error("thumbnail: libswscale did not fill the image");
    return out;
}

}  // namespace render
