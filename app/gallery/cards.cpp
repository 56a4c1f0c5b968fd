// One figure's card: its thumbnail (and poster, preview and film), title,
// source, key numbers, parameters, seed and the numbers it computed.

#include "app/gallery/cards.hpp"

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

namespace app::gallery {

namespace {

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
}  // namespace

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

}  // namespace app::gallery
