#include "figures/catalog.hpp"

#include <algorithm>
#include <cstdlib>

#include "figures/settings.hpp"

namespace figures {

std::filesystem::path catalog_dir() {
    if (const char* dir = std::getenv("FIGGEN_FIGURES_DIR"); dir && *dir) return dir;
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
    if (given.extension() == ".toml" || id_or_path.find('/') != std::string::npos) {
        if (std::filesystem::is_regular_file(given)) return given;
        throw UsageError("figure file " + id_or_path + " does not exist");
    }
    const auto file = catalog_dir() / (id_or_path + ".toml");
    if (std::filesystem::is_regular_file(file)) return file;
    std::string known;
    for (const auto& f : catalog_files()) known += (known.empty() ? "" : ", ") + f.stem().string();
    throw UsageError("unknown figure id '" + id_or_path + "'; known ids: " + known);
}

}  // namespace figures
