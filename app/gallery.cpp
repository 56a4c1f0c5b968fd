#include "app/gallery.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "description/catalog.hpp"
#include "app/version.hpp"
#include "render/atomic_file.hpp"
#include "render/png_io.hpp"
#include "render/thumbnail.hpp"
#include "render/video.hpp"

namespace app {
using description::catalog_files;
namespace {

constexpr int thumb_width = 480, thumb_height = 360;

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
                   std::size_t limit) {
    static const std::vector<std::string> skipped = {
        "id", "title", "source", "scene", "caption", "seed", "description", "figgen_version", "renderer",
        "scale", "params", "style", "image", "state_sha256", "file", "codec", "pixel_format",
        "encoder_threads", "png_sequence", "steps", "memory_estimate"};
    for (const auto& [key, value] : node.items()) {
        if (rows.size() >= limit) return;
        if (std::find(skipped.begin(), skipped.end(), key) != skipped.end()) continue;
        const std::string here = path.empty() ? key : path + "." + key;
        std::string text;
        if (short_value(value, text))
            rows.push_back("<tr><th>" + escape(here) + "</th><td>" + escape(text) + "</td></tr>");
        else if (value.is_object() || value.is_array())
            computed_rows(value, here, rows, limit);
    }
}

std::string parameter_list(const nlohmann::json& meta) {
    std::string html;
    for (const char* section : {"params", "style"}) {
        if (!meta.contains(section) || !meta[section].is_object()) continue;
        for (const auto& [key, value] : meta[section].items()) {
            std::string text = value.is_string() ? value.get<std::string>() : value.dump();
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
.links { margin: 0.5rem 0; font-size: 0.9rem; }
.links a { margin-right: 1rem; }
details { margin-top: 0.4rem; font-size: 0.85rem; }
summary { cursor: pointer; color: var(--muted); }
table { border-collapse: collapse; width: 100%; table-layout: fixed; }
th, td { text-align: left; vertical-align: top; padding: 0.1rem 0.4rem 0.1rem 0; overflow-wrap: anywhere; }
th { font-weight: normal; color: var(--muted); width: 42%; }
td { font-family: "DejaVu Sans Mono", monospace; }
)";

}  // namespace

int write_thumbnails(const std::filesystem::path& from, const std::filesystem::path& to, int max_width,
                     int max_height) {
    std::filesystem::create_directories(to);
    int written = 0;
    for (const auto& file : catalog_files()) {
        const std::string id = file.stem().string();
        if (!std::filesystem::exists(from / (id + ".png"))) continue;
        const render::PngFile png = render::read_png(from / (id + ".png"));
        std::string title = id;
        for (const auto& [key, value] : png.text)
            if (key == "Title") title = value;
        render::write_png(to / (id + ".png"), render::thumbnail(png.image, max_width, max_height), {{"Title", title}});
        ++written;
    }
    return written;
}

namespace {

// The card's <video>, where the metadata names a film and its file is there;
// writes its poster, the film's last frame decoded from the MP4: what the
// film grows into, where the first frame (what a browser shows by itself)
// is often nearly empty. Returns the film's file name, or "" for none.
std::string film_html(const std::filesystem::path& dir, const std::string& id, const std::string& title,
                      const nlohmann::json& meta, std::ostringstream& card) {
    const nlohmann::json film = meta.value("animation", nlohmann::json::object());
    const std::string movie = film.value("file", "");
    if (movie.empty() || !std::filesystem::exists(dir / movie)) return "";
    const int width = film["size"][0].get<int>(), height = film["size"][1].get<int>();
    const int frames = film["frames"].get<int>();
    render::write_png(dir / "posters" / (id + ".png"), render::decode_frame(dir / movie, frames - 1, 0),
                      {{"Title", title + " (last frame of " + movie + ")"}});
    card << "<video controls preload=\"metadata\" src=\"" << escape(movie) << "\" poster=\"posters/" << escape(id)
         << ".png\" width=\"" << width << "\" height=\"" << height << "\" data-width=\"" << width
         << "\" data-height=\"" << height << "\" data-frames=\"" << frames << "\" data-fps=\""
         << film["fps"].get<int>() << "\"></video>\n";
    return movie;
}

// The links and the collapsible tables below a card's pictures.
void details_html(const std::string& id, const std::string& movie, const nlohmann::json& meta,
                  std::ostringstream& card) {
    card << "<div class=\"links\"><a href=\"" << escape(id) << ".png\">full PNG";
    if (meta.contains("image")) {
        const auto& size = meta["image"]["size"];
        card << " (" << size[0].get<int>() << " x " << size[1].get<int>() << ")";
    }
    card << "</a><a href=\"" << escape(id) << ".json\">metadata</a>";
    if (!movie.empty()) card << "<a href=\"" << escape(movie) << "\">MP4</a>";
    card << "</div>\n"
         << "<details><summary>parameters, seed " << meta.value("seed", 0ull) << "</summary><table>"
         << "<tr><th>seed</th><td>" << meta.value("seed", 0ull) << "</td></tr>" << parameter_list(meta)
         << "</table></details>\n";
    std::vector<std::string> numbers;
    computed_rows(meta, "", numbers, 40);
    if (!numbers.empty()) {
        card << "<details><summary>computed numbers</summary><table>";
        for (const auto& row : numbers) card << row;
        card << "</table></details>\n";
    }
    if (!meta.value("caption", "").empty())
        card << "<details><summary>notes</summary><p>" << escape(meta.value("caption", "")) << "</p></details>\n";
}

// One figure's card; writes its thumbnail (and poster).
std::string card_html(const std::filesystem::path& dir, const std::string& id, const nlohmann::json& meta) {
    const render::Image thumb =
        render::thumbnail(render::read_png(dir / (id + ".png")).image, thumb_width, thumb_height);
    render::write_png(dir / "thumbs" / (id + ".png"), thumb, {{"Title", meta.value("title", id)}});
    const std::string title = meta.value("title", id);
    std::ostringstream card;
    card << "<article id=\"" << escape(id) << "\">\n"
         << "<h2>" << escape(title) << "</h2>\n"
         << "<div class=\"id\">" << escape(id) << "</div>\n"
         << "<p class=\"source\">" << escape(meta.value("source", "")) << "</p>\n"
         << "<a href=\"" << escape(id) << ".png\"><img src=\"thumbs/" << escape(id) << ".png\" width=\""
         << thumb.width << "\" height=\"" << thumb.height << "\" alt=\"" << escape(title) << "\"></a>\n";
    const std::string movie = film_html(dir, id, title, meta, card);
    details_html(id, movie, meta, card);
    card << "</article>\n";
    return card.str();
}

std::string page_html(const std::string& cards, int shown, int missing) {
    std::ostringstream page;
    page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         << "<link rel=\"icon\" href=\"data:,\">\n"  // no favicon request
         << "<title>figgen gallery</title>\n<style>" << style_sheet << "</style>\n</head>\n<body>\n"
         << "<header><h1>figgen gallery</h1>\n<p>" << shown << " figure" << (shown == 1 ? "" : "s")
         << " rendered by figgen " << escape(version()) << " from the descriptions in figures/";
    if (missing > 0) page << "; " << missing << " of the catalog not rendered here";
    page << ".</p></header>\n<main>\n" << cards << "</main>\n</body>\n</html>\n";
    return page.str();
}

}  // namespace

int write_gallery(const std::filesystem::path& dir) {
    std::string cards;
    int shown = 0, missing = 0;
    std::filesystem::create_directories(dir / "thumbs");
    std::filesystem::create_directories(dir / "posters");
    for (const auto& file : catalog_files()) {
        const std::string id = file.stem().string();
        std::ifstream in(dir / (id + ".json"));
        if (!in || !std::filesystem::exists(dir / (id + ".png"))) {
            ++missing;
            continue;
        }
        cards += card_html(dir, id, nlohmann::json::parse(in));
        ++shown;
    }
    render::write_file_atomically(dir / "index.html", page_html(cards, shown, missing));
    return shown;
}

}  // namespace app
