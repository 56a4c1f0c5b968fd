#pragma once
// PNG files through libpng: 8-bit RGBA, text chunks for the parameters and
// seed, no timestamp (the same figure gives the same bytes).

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "render/image.hpp"

namespace render {

using TextChunks = std::vector<std::pair<std::string, std::string>>;  // keyword, Latin-1 text

// Writes atomically (temporary name, then rename); throws std::runtime_error
// naming the file and the reason, leaving nothing under `path` on failure.
void write_png(const std::filesystem::path& path, const Image& image, const TextChunks& text = {});

struct PngFile {
    Image image;      // converted to 8-bit RGBA whatever the file's format
    TextChunks text;  // tEXt/zTXt/iTXt chunks in file order
};
PngFile read_png(const std::filesystem::path& path);

}  // namespace render
