#pragma once
// The figure descriptions shipped in figures/: finding one by id or path.

#include <filesystem>
#include <string>
#include <vector>

namespace description {

// The folder of descriptions: $FIGGEN_FIGURES_DIR, else PREFIX/share/figgen/figures
// beside an installed PREFIX/bin/figgen, else the source tree's figures/.
std::filesystem::path catalog_dir();

// Every *.toml in the catalog, sorted by file name.
std::vector<std::filesystem::path> catalog_files();

// A description file for `id_or_path`: an existing file as given, else
// <catalog>/<id>.toml. Throws UsageError naming the closest ids.
std::filesystem::path resolve_figure(const std::string& id_or_path);

// The `count` catalog ids nearest to `id`: those containing it first, then
// by edit distance (ties in file-name order): what an unknown id was
// probably meant to be.
std::vector<std::string> closest_ids(const std::string& id, std::size_t count);

}  // namespace description
