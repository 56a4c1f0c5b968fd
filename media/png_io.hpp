#pragma once
// PNG files through libpng: 8-bit RGBA (RGB when every pixel is opaque), text chunks for the parameters and
// seed, no timestamp (the same figure gives the same bytes).

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "base/atomic_file.hpp"
#include "render/image.hpp"

namespace media {

using render::any_pixels;
using render::Image;
using render::ImageTooLarge;

using TextChunks = std::vector<std::pair<std::string, std::string>>;  // keyword, Latin-1 text

// How hard zlib works. A figure is kept small (zlib level 4, and libpng's
// adaptive filters or none, whichever a sample of the rows compresses
// better; see png_io.cpp); a film's PNG sequence, hundreds of frames, is
// written fast (level 1, the Sub filter): tc7-2's 351 frames take 7.5 s
// instead of 30.3 s, at 94 MB instead of 71.
enum class PngCompression { smallest, fast };

// Writes folder/name atomically (an exclusive temporary, then rename; see
// atomic_file.hpp); throws std::runtime_error naming the file and the
// reason, leaving nothing under the name on failure.
void write_png(const base::Folder& folder, const std::string& name, const Image& image, const TextChunks& text = {},
               base::AtomicFile::Commit when = base::AtomicFile::Commit::with_group,
               PngCompression compression = PngCompression::smallest);
// The same, for a path whose folder is the caller's.
void write_png(const std::filesystem::path& path, const Image& image, const TextChunks& text = {});

struct PngFile {
    Image image;      // converted to 8-bit RGBA whatever the file's format
    TextChunks text;  // tEXt/zTXt/iTXt chunks in file order
};
PngFile read_png(const std::filesystem::path& path);
// folder/name, which must be a regular file there (a symlink is not
// followed, a FIFO not waited on). An image whose header (png_read_info)
// claims more than `max_pixels` pixels throws ImageTooLarge before any
// pixel is allocated.
PngFile read_png(const base::Folder& folder, const std::string& name, std::uint64_t max_pixels = any_pixels);

}  // namespace media
