#pragma once
// The rendered folder as the gallery (app/gallery/page.cpp, cards.cpp) and
// the thumbnails read it: every file untrusted. Only regular files (never a
// symlink) named by the catalog or the folder's listing are read, each
// JSON with a size and a depth limit, each image within --max-memory by
// the size its header claims.

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "render/image.hpp"

namespace app::gallery {

constexpr int thumb_width = 480, thumb_height = 360;
// Figures of other descriptions shown at most: a folder of a million JSON
// files makes a long page, not an endless one.
constexpr std::size_t max_other_figures = 1000;

// The gallery's folder (the rendered figures, index.html) and the two it makes.
struct Folders {
    base::Folder figures, thumbs, posters;
};

// What decoding an image takes, to keep it within --max-memory: the
// program itself (figgen with FFmpeg's and libwebp's libraries loaded),
// and bytes a pixel of the size the image's header claims. Measured with
// /usr/bin/time -v (maximum resident set size) on `figgen gallery`: a
// gallery of tc7-1 (with its film) and tc7-9 at half size peaks at 44 MB.
constexpr double program_bytes = 64.0 * 1024 * 1024;
// A PNG: its RGBA pixels, and libswscale's rows as it scales them down
// (measured: 47.6 MB for a 2000 x 2000 PNG, 173.9 MB for 6000 x 6000, 4.04
// bytes a pixel between them).
constexpr double png_bytes_per_pixel = 4.5;
// A film's poster frame: the decoder's frames (H.264 keeps up to 16 for
// reference, and one a decoding thread, of which there are at most
// poster_threads), each 1.5 bytes a pixel in YUV 4:2:0, and the frame in
// RGBA: (16 + 8 + 2) * 1.5 + 4 and libswscale's rows. tc7-1's x264 film
// measured 18 bytes a pixel on 2 threads (53.7 MB at 800 x 800, 143.6 MB
// at 2400 x 2400).
constexpr double film_bytes_per_pixel = 48.0;
constexpr unsigned poster_threads = 8;
// A preview's canvas: libwebp's two canvases (the frame shown and the one
// before it), the frame being decoded, and our copy of it.
constexpr double webp_bytes_per_pixel = 16.0;


// The most pixels an image may claim under `max_memory`, at `bytes_per_pixel`.
std::uint64_t max_pixels(std::uint64_t max_memory, double bytes_per_pixel);
// Why `file` was not read: one line with the size its header claims and
// the memory that would take.
std::string refusal(const std::string& file, const render::ImageTooLarge& e, std::uint64_t max_memory,
                    double bytes_per_pixel);

// What the metadata says, read as untrusted: a missing or mistyped field
// gives the fallback (a null, the text given, 0, -1), never an exception.
const nlohmann::json& member(const nlohmann::json& node, const char* key);
std::string text_of(const nlohmann::json& node, const char* key, const std::string& fallback);
// A positive integer up to a million (a size, a count), else 0.
int count_of(const nlohmann::json& value);
// An index below `limit` (a frame of a film), else -1.
int index_of(const nlohmann::json& value, int limit);

// Whether `name` in `folder` is a file of its own: not a symlink (which
// could lead out of the folder), not a folder.
bool is_file_in(const base::Folder& folder, const std::string& name);
// Whether something other than a regular file (a FIFO, a folder, a
// symlink) stands at `name` in `folder`.
bool is_other_than_file(const base::Folder& folder, const std::string& name);
// The metadata folder/name, read as a regular file (no symlink followed, no
// FIFO waited on); null when it is not there or is not JSON, and also when
// it is not a regular file, is too large or nests too deep, which
// `problem` then says.
nlohmann::json read_metadata(const base::Folder& folder, const std::string& name, std::string* problem = nullptr);
// The figures in the folder that are not the catalog's (at most
// max_other_figures), in name order; what cannot be read is added to
// `unreadable`.
std::vector<std::string> figures_outside(const base::Folder& folder, const std::vector<std::string>& catalog,
                                         std::vector<std::string>& unreadable);

}  // namespace app::gallery
