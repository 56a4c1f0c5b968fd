#pragma once
// An 8-bit RGBA image in memory, rows top to bottom: what the canvas reads
// back and what the PNG and MP4 sinks take.

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
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

// No limit on the pixels a reader may decode.
constexpr std::uint64_t any_pixels = std::numeric_limits<std::uint64_t>::max();

// An image (a PNG, a film's frames, a WebP's canvas) refused before it is
// decoded: its header claims more pixels than the reader was allowed, so
// a few bytes of header cannot make the reader allocate gigabytes.
struct ImageTooLarge : std::runtime_error {
    ImageTooLarge(const std::string& read, std::uint64_t claimed_width, std::uint64_t claimed_height,
                  std::uint64_t allowed)
        : std::runtime_error("cannot read " + read + ": its header claims " + std::to_string(claimed_width) + " x " +
                             std::to_string(claimed_height) + " pixels, more than the " + std::to_string(allowed) +
                             " allowed"),
          file(read),
          width(claimed_width),
          height(claimed_height),
          max_pixels(allowed) {}
    std::string file;             // what was read
    std::uint64_t width, height;  // what the header claims
    std::uint64_t max_pixels;     // what the reader allowed
};

}  // namespace render
