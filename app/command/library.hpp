#pragma once
// figgen's render and describe as library calls, for the Python module
// (python/extension.cpp): one figure in this process, through the same phases,
// options and checks as `figgen render`, and the same bits.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/command/describe.hpp"
#include "app/render/render_settings.hpp"
#include "scenes/output.hpp"

namespace app {

struct RenderRequest {
    std::string target;               // a catalog id, or a description (.toml) or Ready pattern (.vti) file
    std::optional<std::string> text;  // else the description itself, TOML; `target` names it in messages
    RenderSettings settings;          // as figgen render's options; formats empty: png and the film
};

struct RenderResult {
    std::string id;
    std::filesystem::path json;                // the figure's metadata
    std::vector<std::filesystem::path> files;  // every file it wrote, in the format table's order
};

// Renders the figure: phase 1 (every setting, the memory and disk
// estimates) before anything runs, then the run and its files, put in
// place together or not at all. Throws SettingError for a refused setting,
// UsageError for other refused input, and what `progress` throws, having
// written nothing. Renders share the process's one GL context: a request
// for another GL platform than the first render's is refused.
RenderResult render_request(const RenderRequest& request, scenes::Progress& progress);

// Every setting of the figure `target` names, or of the description `text`.
Described describe_request(const std::string& target, const std::optional<std::string>& text);

}  // namespace app
