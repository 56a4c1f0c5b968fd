#include "figures/scene.hpp"

#include "render/text.hpp"

#include <system_error>

namespace figures {
namespace {

// A model's range check names its parameter first ("tc7-1: r = 0.5 is not
// allowed: ..."); say where that parameter was given when it was.
std::string located(const Description& d, const std::string& message) {
    const std::string prefix = d.id + ": ";
    if (message.rfind(prefix, 0) != 0) return message;
    const std::string rest = message.substr(prefix.size());
    const auto end = rest.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_");
    if (end == 0 || end == std::string::npos || rest.compare(end, 3, " = ") != 0) return message;
    for (const char* section : {"params.", "style."})
        if (const auto found = d.origins.find(section + rest.substr(0, end)); found != d.origins.end())
            return found->second + ": " + rest;
    return message;
}

}  // namespace

const std::vector<SceneInfo>& scenes() {
    static const std::vector<SceneInfo> all = {
        {"diffusion", render_diffusion},
        {"gray_scott", render_gray_scott},
        {"gray_scott_atlas", render_gray_scott_atlas},
        {"percolation", render_percolation},
        {"percolation_sizes", render_percolation_sizes},
        {"cell1d", render_cell1d},
        {"cell_counts", render_cell_counts},
        {"percolation_scaling", render_percolation_scaling},
        {"percolation_phase", render_percolation_phase},
        {"forest_fire", render_forest_fire},
        {"cell1d_survey", render_cell1d_survey},
        {"snowflake", render_snowflake},
        {"snowflake_dimension", render_snowflake_dimension},
        {"hex_lattice", render_hex_lattice},
        {"phyllotaxis", render_phyllotaxis},
        {"ifs", render_ifs},
        {"deposition", render_deposition},
        {"roughness", render_roughness},
        {"lsystem", render_lsystem},
        {"lsystem_3d", render_lsystem_3d},
    };
    return all;
}

void render_figure(const Description& d, const OutputOptions& options, Progress& progress) {
    for (const SceneInfo& scene : scenes()) {
        if (scene.model != d.model) continue;
        std::error_code ec;
        std::filesystem::create_directories(options.dir, ec);
        if (ec || !std::filesystem::is_directory(options.dir))
            throw UsageError("--out " + options.dir.string() +
                             ": cannot create the folder: " + (ec ? ec.message() : "not a directory"));
        require_disk(d, options);
        require_memory(d, options, {});
        render::clear_font_cache();  // same pixels whatever was rendered before in this process
        try {
            scene.render(d, options, progress);
        } catch (const KeyError& e) {
            throw UsageError(d.where(e.key) + ": " + e.what());
        } catch (const UsageError& e) {
            throw UsageError(located(d, e.what()));
        }
        return;
    }
    std::string allowed;
    for (const SceneInfo& scene : scenes()) allowed += (allowed.empty() ? "" : ", ") + scene.model;
    throw UsageError(d.file.filename().string() + ": model \"" + d.model + "\" is unknown; allowed: " + allowed);
}

}  // namespace figures
