#pragma once
// An 8-bit RGBA image in memory, rows top to bottom: what the canvas reads
// back and what the PNG and MP4 sinks take.

#include <cstdint>
#include <vector>

namespace render {

struct Image {
    int width = 0;                 // pixels
    int height = 0;                // pixels
    std::vector<std::uint8_t> rgba;  // width*height*4 bytes, row 0 is the top

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0) {}

    std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
    const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

}  // namespace render
