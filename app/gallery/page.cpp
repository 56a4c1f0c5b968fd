// The gallery's page, out/index.html: the catalog's cards, then the
// other figures figgen wrote into the folder.

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

#include "app/gallery/cards.hpp"
#include "app/gallery/folder.hpp"

namespace app {

using description::catalog_files;
using namespace gallery;

namespace {

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
