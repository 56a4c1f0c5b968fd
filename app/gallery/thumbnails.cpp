// The README's thumbnails: the catalog's PNGs and film previews, smaller.

#include "app/gallery/gallery.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/gallery/key_numbers.hpp"
#include "app/render/formats.hpp"
#include "app/render/output_files.hpp"
#include "app/work/bounded_json.hpp"
#include "base/atomic_file.hpp"
#include "base/version.hpp"
#include "description/catalog.hpp"
#include "description/plain_name.hpp"
#include "media/png_io.hpp"
#include "media/thumbnail.hpp"
#include "media/video.hpp"

#include "app/gallery/folder.hpp"

namespace app {

using description::catalog_files;
using namespace gallery;

ThumbnailsWritten write_thumbnails(const std::filesystem::path& from, const std::filesystem::path& to, int max_width,
                                   int max_height, std::uint64_t max_memory) {
    const base::Folder source(from), target(to, true);
    ThumbnailsWritten made;
    // A file that cannot be read is named and passed over; the error
    // names the file and says why (not a regular file, not an image, or a
    // header claiming more than --max-memory allows).
    const auto refused = [&](const std::string& name, const std::exception& e) {
        const auto* large = dynamic_cast<const render::ImageTooLarge*>(&e);
        const double per_pixel = name.ends_with(".webp") ? webp_bytes_per_pixel : png_bytes_per_pixel;
        made.refused.push_back(large ? refusal((source / name).string(), *large, max_memory, per_pixel) : e.what());
    };
    for (const auto& file : catalog_files()) {
        const std::string id = file.stem().string();
        if (!is_file_in(source, id + ".png")) continue;
        media::PngFile png;
        try {
            png = media::read_png(source, id + ".png", max_pixels(max_memory, png_bytes_per_pixel));
        } catch (const std::runtime_error& e) {
            refused(id + ".png", e);
            continue;
        }
        std::string title = id;
        for (const auto& [key, value] : png.text)
            if (key == "Title") title = value;
        media::write_png(target, id + ".png", media::thumbnail(png.image, max_width, max_height),
                          {{"Title", title}});
        // A film's preview as an animated thumbnail too, for pages that
        // show the animated figures moving (the README's grid): half the
        // preview's frames, within 400 KB.
        if (is_file_in(source, id + ".webp")) {
            media::PreviewOptions small;
            small.max_width = max_width;
            small.max_height = max_height;
            small.max_frames = 24;
            small.max_bytes = 400u << 10;
            try {
                media::write_preview_thumbnail(source, id + ".webp", target, id + ".webp", small,
                                                max_pixels(max_memory, webp_bytes_per_pixel));
            } catch (const std::runtime_error& e) {
                refused(id + ".webp", e);
            }
        }
        ++made.written;
    }
    return made;
}

}  // namespace app
