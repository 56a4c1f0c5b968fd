#pragma once
// The gallery: out/index.html, one card per rendered figure of the catalog,
// then one per other figure figgen wrote into the folder, each with its
// thumbnail (out/thumbs/ID.png), title, source, its key results beside the
// catalog's reference values (app/key_numbers.hpp), parameters and seed, the
// numbers its metadata computed, links to the full PNG and the metadata, and
// the MP4 as a <video> where there is one, its poster the frame the
// description names (animation.poster), else the film's last frame
// (out/posters/ID.png). Plain HTML and CSS in one file, no scripts, nothing
// fetched from the network; one column on a phone, a grid on a wide screen.
// Every file in the folder is untrusted: the gallery reads only regular files
// (never a symlink) named by the catalog or the folder's listing, never a
// name taken from a JSON, and escapes every text it shows.

#include <filesystem>

namespace app {

// Reads every DIR/ID.json of the catalog's ids (figures not rendered are left
// out, and counted in the page's header), then every other DIR/ID.json that
// figgen wrote (its "id" is ID and it has "figgen_version") with its
// DIR/ID.png, and writes DIR/index.html, the thumbnails and the posters,
// each atomically. Returns the number of figures shown.
int write_gallery(const std::filesystem::path& dir);

// TO/ID.png for every DIR/ID.png of the catalog's ids, scaled to fit
// max_width x max_height (the README's grid: `make readme-thumbnails`).
// Returns how many were written.
int write_thumbnails(const std::filesystem::path& from, const std::filesystem::path& to, int max_width,
                     int max_height);

}  // namespace app
