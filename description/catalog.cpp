#include "description/catalog.hpp"

#include <algorithm>
#include <cstdlib>

#include "base/module.hpp"
#include "description/plain_name.hpp"
#include "description/settings.hpp"

namespace description {
namespace {

// Levenshtein distance: insertions, deletions and substitutions, one each.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

}  // namespace

std::vector<std::string> closest_ids(const std::string& id, std::size_t count) {
    // Ids that contain what was typed come first ("lycopodium"), then by distance ("tc7-10").
    std::vector<std::pair<std::size_t, std::string>> ranked;
    for (const auto& f : catalog_files()) {
        const std::string known = f.stem().string();
        const bool contains = !id.empty() && known.find(id) != std::string::npos;
        ranked.emplace_back(contains ? 0 : 1 + edit_distance(id, known), known);
    }
    std::stable_sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<std::string> ids;
    for (std::size_t i = 0; i < std::min(count, ranked.size()); ++i) ids.push_back(ranked[i].second);
    return ids;
}

std::filesystem::path catalog_dir() {
    if (const char* dir = std::getenv("FIGGEN_FIGURES_DIR"); dir && *dir) return dir;
    // An installed figgen (PREFIX/bin/figgen) reads PREFIX/share/figgen/figures.
    std::error_code ec;
    if (const std::filesystem::path folder = base::program_folder(); !folder.empty()) {
        const auto installed = folder.parent_path() / "share" / "figgen" / "figures";
        if (std::filesystem::is_directory(installed, ec)) return installed;
    }
    return FIGGEN_FIGURES_DIR;
}

std::vector<std::filesystem::path> catalog_files() {
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(catalog_dir(), ec))
        if (entry.is_regular_file() && entry.path().extension() == ".toml") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::filesystem::path resolve_figure(const std::string& id_or_path) {
    const std::filesystem::path given(id_or_path);
    std::error_code ec;  // a name the file system refuses (too long, say) is a file that is not there
    if (given.extension() == ".toml" || id_or_path.find('/') != std::string::npos) {
        if (std::filesystem::is_regular_file(given, ec)) return given;
        if (std::filesystem::exists(given, ec))
            throw UsageError("figure file " + printable_short(id_or_path, 200) +
                             " is not allowed: a description is a regular .toml file");
        throw UsageError("figure file " + printable_short(id_or_path, 200) + " does not exist");
    }
    if (is_plain_id(id_or_path)) {
        const auto file = catalog_dir() / (id_or_path + ".toml");
        if (std::filesystem::is_regular_file(file, ec)) return file;
    }
    std::string closest;
    for (const auto& id : closest_ids(id_or_path.substr(0, 200), 3)) closest += (closest.empty() ? "" : ", ") + id;
    throw UsageError("unknown figure id '" + printable_short(id_or_path, 100) + "'; closest: " + closest +
                     " (`figgen list` shows all " + std::to_string(catalog_files().size()) + ")");
}

}  // namespace description
