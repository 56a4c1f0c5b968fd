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

namespace app {
using description::catalog_files;
namespace {

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
std::uint64_t max_pixels(std::uint64_t max_memory, double bytes_per_pixel) {
    const double room = static_cast<double>(max_memory) - program_bytes;
    return room <= 0 ? 0 : static_cast<std::uint64_t>(room / bytes_per_pixel);
}

// Why `file` was not read: one line with the size its header claims and
// the memory that would take.
std::string refusal(const std::string& file, const render::ImageTooLarge& e, std::uint64_t max_memory,
                    double bytes_per_pixel) {
    const double needs = program_bytes + bytes_per_pixel * static_cast<double>(e.width) * static_cast<double>(e.height);
    return file + " is not decoded: its header claims " + std::to_string(e.width) + " x " + std::to_string(e.height) +
           " pixels, which would take about " + format_bytes(needs) + " to decode, more than --max-memory " +
           format_bytes(static_cast<double>(max_memory));
}

std::string escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

// What the metadata says, read as untrusted: a missing or mistyped field
// gives the fallback, never an exception.
const nlohmann::json& member(const nlohmann::json& node, const char* key) {
    static const nlohmann::json none;
    if (!node.is_object()) return none;
    const auto found = node.find(key);
    return found == node.end() ? none : *found;
}
std::string text_of(const nlohmann::json& node, const char* key, const std::string& fallback) {
    const nlohmann::json& value = member(node, key);
    return value.is_string() ? value.get<std::string>() : fallback;
}
// A positive integer up to a million (a size, a count), else 0.
int count_of(const nlohmann::json& value) {
    return value.is_number_integer() && value.get<long long>() > 0 && value.get<long long>() <= 1'000'000
               ? static_cast<int>(value.get<long long>())
               : 0;
}
// An index below `limit` (a frame of a film), else -1.
int index_of(const nlohmann::json& value, int limit) {
    return value.is_number_integer() && value.get<long long>() >= 0 && value.get<long long>() < limit
               ? static_cast<int>(value.get<long long>())
               : -1;
}
std::string seed_of(const nlohmann::json& meta) {
    const nlohmann::json& seed = member(meta, "seed");
    return seed.is_number_unsigned() ? std::to_string(seed.get<std::uint64_t>()) : "?";
}

std::string number_text(const nlohmann::json& value) {
    if (value.is_number_float()) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", value.get<double>());
        return text;
    }
    if (value.is_string()) return value.get<std::string>();
    return value.dump();
}

// A short list of values: numbers and short strings in full, a long list as
// its length and ends, a hash or a nested table left out.
bool short_value(const nlohmann::json& value, std::string& text) {
    if (value.is_number() || value.is_boolean()) {
        text = number_text(value);
        return true;
    }
    if (value.is_string()) {
        text = value.get<std::string>();
        return text.size() <= 80;
    }
    if (value.is_array() && !value.empty() &&
        std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); })) {
        std::string list;
        const std::size_t n = value.size();
        for (std::size_t i = 0; i < n; ++i) {
            if (n > 8 && i == 3) {
                list += ", ... (" + std::to_string(n) + " values) ...";
                i = n - 3;
            }
            list += (list.empty() ? "" : ", ") + number_text(value[i]);
        }
        text = "[" + list + "]";
        return true;
    }
    return false;
}

// The numbers a figure computed: every short value in its metadata outside
// the fields every figure has, with its path ("panels.2.statistics.max"),
// hashes and file bookkeeping left out; at most `limit` rows.
void computed_rows(const nlohmann::json& node, const std::string& path, std::vector<std::string>& rows,
                   std::size_t limit, int depth = 0) {
    static const std::vector<std::string> skipped = {
        "id", "title", "source", "scene", "caption", "seed", "description", "figgen_version", "renderer",
        "scale", "params", "style", "image", "state_sha256", "file", "codec", "pixel_format",
        "encoder_threads", "segment_frames", "preset", "tune", "png_sequence", "steps", "memory_estimate"};
    for (const auto& [key, value] : node.items()) {
        if (rows.size() >= limit) return;
        if (std::find(skipped.begin(), skipped.end(), key) != skipped.end()) continue;
        const std::string here = path.empty() ? key : path + "." + key;
        std::string text;
        if (short_value(value, text))
            rows.push_back("<tr><th>" + escape(here) + "</th><td>" + escape(text) + "</td></tr>");
        else if ((value.is_object() || value.is_array()) && depth < 6)
            computed_rows(value, here, rows, limit, depth + 1);
    }
}

// `value` as JSON text, cut at about `limit` characters and 8 levels deep
// ("..."): a hand-made metadata nested a million levels deep must not take
// the serializer's recursion with it.
void brief_into(const nlohmann::json& value, std::size_t limit, int depth, std::string& text) {
    if (text.size() > limit) return;
    if (!value.is_structured()) {
        text += value.dump();
        return;
    }
    const bool object = value.is_object();
    text += object ? "{" : "[";
    if (depth >= 8 && !value.empty()) text += "...";
    else {
        bool first = true;
        for (const auto& [key, item] : value.items()) {
            if (text.size() > limit) break;
            if (!first) text += ",";
            first = false;
            if (object) text += nlohmann::json(key).dump() + ":";
            brief_into(item, limit, depth + 1, text);
        }
    }
    text += object ? "}" : "]";
}
std::string brief(const nlohmann::json& value, std::size_t limit) {
    std::string text;
    brief_into(value, limit, 0, text);
    return text;
}

std::string parameter_list(const nlohmann::json& meta) {
    std::string html;
    for (const char* section : {"params", "style"}) {
        if (!meta.contains(section) || !meta[section].is_object()) continue;
        for (const auto& [key, value] : meta[section].items()) {
            std::string text = value.is_string() ? value.get<std::string>() : brief(value, 120);
            if (text.size() > 120) text = text.substr(0, 117) + "...";
            html += "<tr><th>" + escape(std::string(section) == "params" ? key : "style." + key) + "</th><td>" +
                    escape(text) + "</td></tr>";
        }
    }
    return html;
}

const char* style_sheet = R"(
:root { color-scheme: light; --ink: #1d2430; --muted: #5b6577; --line: #d8dde6; }
* { box-sizing: border-box; }
body { margin: 0; font: 16px/1.5 "DejaVu Sans", system-ui, sans-serif; color: var(--ink); background: #f5f6f8; }
header { padding: 1.2rem 1rem 0.6rem; max-width: 1400px; margin: 0 auto; }
header h1 { margin: 0 0 0.2rem; font-size: 1.6rem; }
header p { margin: 0.2rem 0; color: var(--muted); }
main { display: grid; gap: 1rem; padding: 1rem; max-width: 1400px; margin: 0 auto;
       grid-template-columns: repeat(auto-fill, minmax(min(100%, 420px), 1fr)); }
article { background: #fff; border: 1px solid var(--line); border-radius: 8px; padding: 0.8rem; min-width: 0; }
article h2 { font-size: 1.1rem; margin: 0 0 0.2rem; }
article .id { font-family: "DejaVu Sans Mono", monospace; font-size: 0.85rem; color: var(--muted); }
article .source { margin: 0.2rem 0 0.6rem; color: var(--muted); font-size: 0.9rem; }
img, video { display: block; max-width: 100%; height: auto; border: 1px solid var(--line); background: #fff; }
video { margin-top: 0.6rem; max-height: 420px; width: auto; }
details.film { margin-top: 0.6rem; font-size: inherit; }
details.film > summary { list-style: none; color: inherit; }
details.film > summary::-webkit-details-marker { display: none; }
details.film > summary span { display: block; font-size: 0.85rem; color: var(--muted); }
details.film[open] > summary img { display: none; }
details.film video { margin-top: 0.2rem; }
.refused { color: #8a1c1c; font-size: 0.9rem; overflow-wrap: anywhere; }
.links { margin: 0.5rem 0; font-size: 0.9rem; }
.links a { margin-right: 1rem; }
details { margin-top: 0.4rem; font-size: 0.85rem; }
summary { cursor: pointer; color: var(--muted); }
table { border-collapse: collapse; width: 100%; table-layout: fixed; }
th, td { text-align: left; vertical-align: top; padding: 0.1rem 0.4rem 0.1rem 0; overflow-wrap: anywhere; }
th { font-weight: normal; color: var(--muted); width: 42%; }
td { font-family: "DejaVu Sans Mono", monospace; }
table.key { margin: 0.4rem 0 0.2rem; font-size: 0.9rem; }
table.key caption { text-align: left; color: var(--muted); font-size: 0.85rem; }
table.key thead th { font-size: 0.8rem; border-bottom: 1px solid var(--line); }
table.key thead th:first-child { width: 34%; }
table.key th { width: auto; }
table.key td.reference { font-family: inherit; color: var(--muted); font-size: 0.85rem; }
)";

}  // namespace

namespace {

// Whether `name` in `folder` is a file of its own: not a symlink (which could
// lead out of the folder), not a folder.
bool is_file_in(const base::Folder& folder, const std::string& name) {
    struct stat st {};
    return ::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
}

// A figure's metadata is at most 16 MiB and nests at most 64 levels (the
// catalog's nest 5): the parser stops deeper, so that a hand-made JSON of a
// million nested `[` is refused as it is read, never walked, copied or
// dumped by recursion.
constexpr std::size_t max_metadata_bytes = 16u << 20;
constexpr int max_metadata_depth = most_nesting;

// Whether something other than a regular file (a FIFO, a folder, a
// symlink) stands at `name` in `folder`.
bool is_other_than_file(const base::Folder& folder, const std::string& name) {
    struct stat st {};
    return ::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode);
}

// The metadata folder/name, read as a regular file (no symlink followed, no
// FIFO waited on); null when it is not there or is not JSON, and also when
// it is not a regular file, is too large or nests too deep, which
// `problem` then says.
nlohmann::json read_metadata(const base::Folder& folder, const std::string& name, std::string* problem = nullptr) {
    const auto refused = [&](const std::string& why) {
        if (problem) *problem = name + " " + why;
        return nullptr;
    };
    struct stat st {};
    if (::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return nullptr;  // not there
    if (!S_ISREG(st.st_mode)) return refused("is not a regular file");
    if (st.st_size > static_cast<off_t>(max_metadata_bytes))
        return refused("holds more than " + std::to_string(max_metadata_bytes >> 20) + " MiB");
    // Read through a descriptor checked again: the name may have changed since.
    const std::optional<std::string> text = base::read_file_at(folder, name, max_metadata_bytes);
    if (!text)
        return refused("could not be read as a regular file of at most " + std::to_string(max_metadata_bytes >> 20) +
                       " MiB");
    try {
        return json_bounded(*text, max_metadata_depth);
    } catch (const MalformedData& e) {
        if (std::string_view(e.what()).rfind("nests", 0) == 0) return refused(e.what());
        return nlohmann::json(nlohmann::json::value_t::discarded);  // not JSON: as before, no card data
    }
}

// The figures in the folder that are not the catalog's: every ID.json
// figgen wrote (an object whose "id" is its file's name, a plain id, and
// which names the figgen that wrote it) beside its ID.png, in name order.
// Names come from the folder's listing, never from a JSON; symlinks are
// passed over, as everywhere in the gallery.
std::vector<std::string> figures_outside(const base::Folder& folder, const std::vector<std::string>& catalog,
                                         std::vector<std::string>& unreadable) {
    std::vector<std::string> ids;
    const int fd = ::openat(folder.fd(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return ids;
    DIR* listing = ::fdopendir(fd);
    if (!listing) {
        ::close(fd);
        return ids;
    }
    while (const dirent* entry = ::readdir(listing)) {
        const std::string name = entry->d_name;
        if (name.size() <= 5 || name.compare(name.size() - 5, 5, ".json") != 0) continue;
        const std::string id = name.substr(0, name.size() - 5);
        if (!description::is_plain_id(id) || std::find(catalog.begin(), catalog.end(), id) != catalog.end()) continue;
        if (!is_file_in(folder, name) || !is_file_in(folder, id + ".png")) continue;
        ids.push_back(id);
        if (ids.size() >= max_other_figures) break;
    }
    ::closedir(listing);
    std::sort(ids.begin(), ids.end());
    std::erase_if(ids, [&](const std::string& id) {
        std::string problem;
        const nlohmann::json meta = read_metadata(folder, id + ".json", &problem);
        if (!problem.empty()) unreadable.push_back(id + ": " + problem);
        return !(meta.is_object() && text_of(meta, "id", "") == id && !text_of(meta, "figgen_version", "").empty());
    });
    return ids;
}

}  // namespace

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

namespace {

// Which film and frame a poster shows: the film's name, size, inode and
// time of its last change (a render puts a new file in place), and the frame.
std::string film_identity(const base::Folder& folder, const std::string& movie, int frame) {
    struct stat st {};
    if (::fstatat(folder.fd(), movie.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return "";
    return movie + " frame " + std::to_string(frame) + ", " + std::to_string(st.st_size) + " bytes, file " +
           std::to_string(st.st_ino) + ", changed " + std::to_string(st.st_mtim.tv_sec) + "." +
           std::to_string(st.st_mtim.tv_nsec);
}

// The PNG's tEXt `key`, or "" (also for a PNG that cannot be read, or
// whose header claims more than `max_pixels`).
std::string png_text(const base::Folder& folder, const std::string& name, const std::string& key,
                     std::uint64_t max_pixels) {
    try {
        for (const auto& [k, value] : media::read_png(folder, name, max_pixels).text)
            if (k == key) return value;
    } catch (const std::exception&) {
    }
    return "";
}

// The card's animated preview, where the figure's ID.webp is in the folder
// (its name is never taken from the metadata): an <img> of the size its
// header gives, or "" for none (also for a file that is not a WebP, and for
// one whose header claims more than --max-memory allows, which `refused`
// then says).
std::string preview_html(const Folders& folders, std::uint64_t max_memory, const std::string& id,
                         const std::string& title, std::string& refused) {
    const std::string preview = id + ".webp";
    if (!is_file_in(folders.figures, preview)) return "";
    try {
        const media::PreviewInfo canvas = media::preview_canvas(folders.figures, preview);
        const std::uint64_t pixels =
            static_cast<std::uint64_t>(canvas.width) * static_cast<std::uint64_t>(canvas.height);
        const std::uint64_t allowed = max_pixels(max_memory, webp_bytes_per_pixel);
        if (pixels > allowed) {
            refused = refusal(preview,
                              render::ImageTooLarge(preview, static_cast<std::uint64_t>(canvas.width),
                                                    static_cast<std::uint64_t>(canvas.height), allowed),
                              max_memory, webp_bytes_per_pixel);
            return "";
        }
        return "<img class=\"preview\" src=\"" + escape(preview) + "\" width=\"" + std::to_string(canvas.width) +
               "\" height=\"" + std::to_string(canvas.height) + "\" alt=\"" + escape(title) +
               " (animated preview; open to play the film)\">";
    } catch (const std::runtime_error&) {
        return "";
    }
}

// The card's <video>, where the figure's film ID.mp4 is in the folder (its
// name is never taken from the metadata). Its poster, posters/ID.png, is the
// frame the description named (animation.poster: the metadata gives its
// index), else the film's last frame, decoded from the MP4: what the film is
// about, where the first frame (what a browser shows by itself) is often
// nearly empty. A poster that cannot be decoded (a hand-edited metadata that
// promises more frames than the film has) is left out. Where the film has
// its animated preview ID.webp, the card shows the preview until the film
// is opened to play (a <details> whose summary is the preview), the poster
// frame then being the <video>'s poster. A film whose header claims frames
// of more pixels than --max-memory allows is not decoded, and the card says
// so in its place. Returns the film's file name, or "" for none.
std::string film_html(const Folders& folders, std::uint64_t max_memory, const std::string& id, const std::string& title,
                      const nlohmann::json& meta, std::ostringstream& card) {
    const std::string movie = id + ".mp4";
    const nlohmann::json& film = member(meta, "animation");
    const nlohmann::json& size = member(film, "size");
    const int width = size.is_array() && size.size() == 2 ? count_of(size[0]) : 0;
    const int height = size.is_array() && size.size() == 2 ? count_of(size[1]) : 0;
    const int frames = count_of(member(film, "frames")), fps = count_of(member(film, "fps"));
    if (!is_file_in(folders.figures, movie) || !width || !height || !frames || !fps) return "";
    const int named = index_of(member(member(film, "poster"), "frame"), frames);
    const int poster_frame = named >= 0 ? named : frames - 1;
    std::string poster;
    try {
        // A poster decoded from this very film (its size and time) at this
        // frame by an earlier run is kept: decoding a long film to its last
        // frame is most of the gallery's time.
        const std::string source = film_identity(folders.figures, movie, poster_frame);
        if (source.empty() || !is_file_in(folders.posters, id + ".png") ||
            png_text(folders.posters, id + ".png", "Source", max_pixels(max_memory, png_bytes_per_pixel)) != source) {
            const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, poster_threads));
            const render::Image frame = media::decode_frame(folders.figures, movie, poster_frame, threads,
                                                             max_pixels(max_memory, film_bytes_per_pixel));
            media::write_png(folders.posters, id + ".png", frame,
                              {{"Title", title + " (frame " + std::to_string(poster_frame) + " of " + movie + ")"},
                               {"Source", source}});
        }
        poster = "posters/" + id + ".png";
    } catch (const render::ImageTooLarge& e) {
        card << "<p class=\"refused\">" << escape(refusal(movie, e, max_memory, film_bytes_per_pixel)) << "</p>\n";
        return "";
    } catch (const std::exception&) {
    }
    std::string refused;
    const std::string preview = preview_html(folders, max_memory, id, title, refused);
    if (!refused.empty()) card << "<p class=\"refused\">" << escape(refused) << "</p>\n";
    if (!preview.empty())
        card << "<details class=\"film\"><summary>" << preview << "<span>&#9654; play the film (" << frames
             << " frames at " << fps << " fps)</span></summary>\n";
    card << "<video controls preload=\"metadata\" src=\"" << escape(movie) << "\"";
    if (!poster.empty()) card << " poster=\"" << escape(poster) << "\"";
    card << " width=\"" << width << "\" height=\"" << height << "\" data-width=\"" << width
         << "\" data-height=\"" << height << "\" data-frames=\"" << frames << "\" data-fps=\"" << fps
         << "\" data-poster-frame=\"" << poster_frame << "\" data-poster-width=\"" << width
         << "\" data-poster-height=\"" << height << "\"></video>\n";
    if (!preview.empty()) card << "</details>\n";
    return movie;
}

// The figure's key results (app/gallery/key_numbers.hpp): label, value and the
// catalog's reference value side by side. Each value cell names the JSON
// pointer it came from (data-path), so a reader or a test can find it in the
// metadata the card links to.
void key_numbers_html(const nlohmann::json& meta, std::ostringstream& card) {
    const std::vector<KeyNumberRow> rows = key_numbers(meta);
    if (rows.empty()) return;
    const bool references = std::any_of(rows.begin(), rows.end(), [](const auto& r) { return !r.reference.empty(); });
    card << "<table class=\"key\"><caption>key results</caption><thead><tr><th scope=\"col\">result</th>"
         << "<th scope=\"col\">value</th>" << (references ? "<th scope=\"col\">reference</th>" : "")
         << "</tr></thead><tbody>\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const KeyNumberRow& row = rows[i];
        card << "<tr><th scope=\"row\">" << escape(row.label) << "</th><td data-path=\"" << escape(row.path)
             << "\" data-kind=\"" << escape(row.kind) << "\"";
        if (!row.error_path.empty()) card << " data-error-path=\"" << escape(row.error_path) << "\"";
        card << ">" << escape(row.value) << "</td>";
        // One reference cell for a run of rows that share it (D of five crystals).
        if (references && (i == 0 || row.reference.empty() || rows[i - 1].reference != row.reference)) {
            std::size_t run = 1;
            while (!row.reference.empty() && i + run < rows.size() && rows[i + run].reference == row.reference) ++run;
            card << "<td class=\"reference\"";
            if (run > 1) card << " rowspan=\"" << run << "\"";
            card << ">" << escape(row.reference) << "</td>";
        }
        card << "</tr>\n";
    }
    card << "</tbody></table>\n";
}

// The links and the collapsible tables below a card's pictures.
void details_html(const base::Folder& figures, const std::string& id, const std::string& movie,
                  const nlohmann::json& meta, std::ostringstream& card) {
    card << "<div class=\"links\"><a href=\"" << escape(id) << ".png\">full PNG";
    const nlohmann::json& size = member(member(meta, "image"), "size");
    if (size.is_array() && size.size() == 2 && count_of(size[0]) && count_of(size[1]))
        card << " (" << count_of(size[0]) << " x " << count_of(size[1]) << ")";
    card << "</a><a href=\"" << escape(id) << ".json\">metadata</a>";
    if (!movie.empty()) card << "<a href=\"" << escape(movie) << "\">MP4</a>";
    // The other formats' files its JSON names and the folder holds.
    for (const OutputFormat& f : output_formats()) {
        if (!f.link || f.json.empty()) continue;
        const nlohmann::json* at = &meta;
        for (const char* key : f.json) at = &member(*at, key);
        const std::string file = text_of(*at, "file", "");
        if (file == id + f.suffix && is_file_in(figures, file))
            card << "<a href=\"" << escape(file) << "\">" << f.link << "</a>";
    }
    card << "</div>\n";
    key_numbers_html(meta, card);
    card << "<details><summary>parameters, seed " << seed_of(meta) << "</summary><table>"
         << "<tr><th>seed</th><td>" << seed_of(meta) << "</td></tr>" << parameter_list(meta)
         << "</table></details>\n";
    std::vector<std::string> numbers;
    computed_rows(meta, "", numbers, 40);
    if (!numbers.empty()) {
        card << "<details><summary>computed numbers</summary><table>";
        for (const auto& row : numbers) card << row;
        card << "</table></details>\n";
    }
    if (!text_of(meta, "caption", "").empty())
        card << "<details><summary>notes</summary><p>" << escape(text_of(meta, "caption", "")) << "</p></details>\n";
}

// One figure's card; writes its thumbnail (and poster). A PNG whose header
// claims more pixels than --max-memory allows is not decoded: the card
// says why in the thumbnail's place.
std::string card_html(const Folders& folders, std::uint64_t max_memory, const std::string& id,
                      const nlohmann::json& meta) {
    const std::string title = text_of(meta, "title", id);
    std::ostringstream card;
    card << "<article id=\"" << escape(id) << "\">\n"
         << "<h2>" << escape(title) << "</h2>\n"
         << "<div class=\"id\">" << escape(id) << "</div>\n"
         << "<p class=\"source\">" << escape(text_of(meta, "source", "")) << "</p>\n";
    try {
        const render::Image thumb = media::thumbnail(
            media::read_png(folders.figures, id + ".png", max_pixels(max_memory, png_bytes_per_pixel)).image,
            thumb_width, thumb_height);
        media::write_png(folders.thumbs, id + ".png", thumb, {{"Title", title}});
        card << "<a href=\"" << escape(id) << ".png\"><img src=\"thumbs/" << escape(id) << ".png\" width=\""
             << thumb.width << "\" height=\"" << thumb.height << "\" alt=\"" << escape(title) << "\"></a>\n";
    } catch (const render::ImageTooLarge& e) {
        card << "<p class=\"refused\">" << escape(refusal(id + ".png", e, max_memory, png_bytes_per_pixel)) << "</p>\n";
    }
    const std::string movie = film_html(folders, max_memory, id, title, meta, card);
    details_html(folders.figures, id, movie, meta, card);
    card << "</article>\n";
    return card.str();
}

std::string page_html(const std::string& cards, int shown, int missing, int others,
                      const std::vector<std::string>& unreadable) {
    std::ostringstream page;
    page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         << "<link rel=\"icon\" href=\"data:,\">\n"  // no favicon request
         << "<title>figgen gallery</title>\n<style>" << style_sheet << "</style>\n</head>\n<body>\n"
         << "<header><h1>figgen gallery</h1>\n<p>" << shown << " figure" << (shown == 1 ? "" : "s")
         << " rendered by figgen " << escape(base::version()) << " from the descriptions in figures/";
    if (others > 0) page << " (" << others << " from descriptions outside it)";
    if (missing > 0) page << "; " << missing << " of the catalog not rendered here";
    for (const std::string& failure : unreadable) page << "; could not show " << escape(failure);
    page << ".</p></header>\n<main>\n" << cards << "</main>\n</body>\n</html>\n";
    return page.str();
}

}  // namespace

int write_gallery(const std::filesystem::path& dir, std::uint64_t max_memory) {
    const base::Folder figures(dir);
    const Folders folders{figures, base::Folder(figures, "thumbs"), base::Folder(figures, "posters")};
    std::string cards;
    int shown = 0, missing = 0;
    std::vector<std::string> unreadable;
    // One card; a figure whose files cannot be read (a PNG that is not
    // one) is named in the header instead of stopping the gallery.
    const auto show = [&](const std::string& id, const nlohmann::json& meta) {
        try {
            cards += card_html(folders, max_memory, id, meta);
            ++shown;
        } catch (const std::exception& e) {
            unreadable.push_back(id + ": " + e.what());
        }
    };
    std::vector<std::string> catalog;
    for (const auto& file : catalog_files()) {
        const std::string id = file.stem().string();
        catalog.push_back(id);
        std::string problem;
        const nlohmann::json meta = read_metadata(figures, id + ".json", &problem);
        if (!problem.empty()) unreadable.push_back(id + ": " + problem);
        if (meta.is_object() && is_other_than_file(figures, id + ".png"))
            unreadable.push_back(id + ": " + id + ".png is not a regular file");
        if (!meta.is_object() || !is_file_in(figures, id + ".png")) {
            ++missing;
            continue;
        }
        show(id, meta);
    }
    int others = 0;
    for (const std::string& id : figures_outside(figures, catalog, unreadable)) {
        show(id, read_metadata(figures, id + ".json"));
        ++others;
    }
    base::write_file_atomically(figures, "index.html", page_html(cards, shown, missing, others, unreadable));
    return shown;
}

}  // namespace app
