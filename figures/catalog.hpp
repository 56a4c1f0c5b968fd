#pragma once
// The figure descriptions shipped in figures/: finding one by id or path.

#include <filesystem>
#include <string>
#include <vector>

namespace figures {

// The folder of descriptions: $FIGGEN_FIGURES_DIR, else the source tree's figures/.
std::filesystem::path catalog_dir();

// Every *.toml in the catalog, sorted by file name.
std::vector<std::filesystem::path> catalog_files();

// A description file for `id_or_path`: an existing file as given, else
// <catalog>/<id>.toml. Throws UsageError listing the known ids.
std::filesystem::path resolve_figure(const std::string& id_or_path);

}  // namespace figures
