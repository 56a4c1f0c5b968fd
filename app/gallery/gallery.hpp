#pragma once
// The gallery: out/index.html, one card per rendered figure of the catalog,
// then one per other figure figgen wrote into the folder, each with its
// thumbnail (out/thumbs/ID.png), title, source, its key results beside the
// catalog's reference values (app/gallery/key_numbers.hpp), parameters and seed, the
// numbers its metadata computed, links to the full PNG and the metadata, and
// the MP4 as a <video> where there is one, its poster the frame the
// description names (animation.poster), else the film's last frame
// (out/posters/ID.png). Plain HTML and CSS in one file, no scripts, nothing
// fetched from the network; one column on a phone, a grid on a wide screen.
// Every file in the folder is untrusted: the gallery reads only regular files
// (never a symlink) named by the catalog or the folder's listing, never a
// name taken from a JSON, and escapes every text it shows.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace app {

// Reads every DIR/ID.json of the catalog's ids (figures not rendered are left
// out, and counted in the page's header), then every other DIR/ID.json that
// figgen wrote (its "id" is ID and it has "figgen_version") with its
// DIR/ID.png, and writes DIR/index.html, the thumbnails and the posters,
// each atomically. A film's card shows its animated preview DIR/ID.webp
// until the film is opened to play, the poster frame being the <video>'s
// poster. An image whose header claims more pixels than `max_memory`
// (--max-memory) allows for decoding it is not decoded: its card says why.
// Every JSON is read with a size and a depth limit. Returns the number of
// figures shown.
int write_gallery(const std::filesystem::path& dir, std::uint64_t max_memory);

struct ThumbnailsWritten {
    int written = 0;                   // TO/ID.png files written
    std::vector<std::string> refused;  // one line each: the file and why it was not read
};

// TO/ID.png for every DIR/ID.png of the catalog's ids, scaled to fit
// max_width x max_height (the README's grid: `make readme-thumbnails`),
// and TO/ID.webp for its film's preview DIR/ID.webp. A file that cannot be
// read (not a regular file, not an image, or a header claiming more pixels
// than `max_memory` allows) is refused, and the others are still written.
ThumbnailsWritten write_thumbnails(const std::filesystem::path& from, const std::filesystem::path& to, int max_width,
                                   int max_height, std::uint64_t max_memory);

}  // namespace app
