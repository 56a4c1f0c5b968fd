#include "figures/scene.hpp"

#include "render/atomic_file.hpp"
#include "render/colormap.hpp"
#include "render/text.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
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

// Two figgen processes rendering the same figure into the same folder take
// turns: otherwise one's PNG could end up beside the other's JSON. The lock
// is a file in the temporary folder named after the output folder's device
// and inode and the id, so the output folder holds nothing but outputs. The
// holder removes it when done; a waiter that then wins a removed file's lock
// sees that the name no longer leads to it and tries again. flock releases
// it when the process ends, however it ends.
class FigureLock {
public:
    FigureLock(const std::filesystem::path& dir, const std::string& id) {
        struct stat folder {};
        if (::stat(dir.c_str(), &folder) != 0) return;  // render_figure has made it; nothing to share then
        std::error_code ec;
        name_ = std::filesystem::temp_directory_path(ec) / ("figgen-" + std::to_string(folder.st_dev) + "-" +
                                                           std::to_string(folder.st_ino) + "-" + id + ".lock");
        if (ec) return;
        for (bool told = false;;) {
            fd_ = ::open(name_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
            if (fd_ < 0) return;  // no temporary folder: no turns, each file is still written whole
            if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
                if (!told)
                    std::fprintf(stderr, "figgen: waiting for another figgen writing %s into %s\n", id.c_str(),
                                 dir.c_str());
                told = true;
                ::flock(fd_, LOCK_EX);
            }
            struct stat held {}, named {};
            if (::fstat(fd_, &held) == 0 && ::stat(name_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
                held.st_dev == named.st_dev)
            {
                render::remove_on_signal(name_);
                return;  // the lock is ours and still the one the name leads to
            }
            ::close(fd_);
        }
    }
    ~FigureLock() {
        if (fd_ < 0) return;
        ::unlink(name_.c_str());  // while still held: see the constructor
        render::keep_on_signal(name_);
        ::close(fd_);
    }
    FigureLock(const FigureLock&) = delete;
    FigureLock& operator=(const FigureLock&) = delete;

private:
    std::filesystem::path name_;
    int fd_ = -1;
};

}  // namespace

const std::vector<SceneInfo>& scenes() {
    static const std::vector<SceneInfo> all = {
        {"diffusion", render_diffusion, {"colormap"}},
        {"gray_scott", render_gray_scott, {"a_colormap", "b_colormap"}},
        {"gray_scott_atlas", render_gray_scott_atlas, {"colormap"}},
        {"percolation", render_percolation, {"colormap"}},
        {"percolation_sizes", render_percolation_sizes, {"colormap"}},
        {"cell1d", render_cell1d, {"colormap"}},
        {"cell_counts", render_cell_counts},
        {"percolation_scaling", render_percolation_scaling},
        {"percolation_phase", render_percolation_phase},
        {"forest_fire", render_forest_fire, {"colormap"}},
        {"cell1d_survey", render_cell1d_survey, {"colormap"}},
        {"snowflake", render_snowflake},
        {"snowflake_dimension", render_snowflake_dimension},
        {"hex_lattice", render_hex_lattice},
        {"phyllotaxis", render_phyllotaxis},
        {"ifs", render_ifs, {"colormap"}},
        {"deposition", render_deposition, {"band_colormap"}},
        {"roughness", render_roughness},
        {"lsystem", render_lsystem},
        {"lsystem_3d", render_lsystem_3d},
    };
    return all;
}

void apply_colormap(Description& d, const std::string& name) {
    const auto names = render::colormap_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string allowed;
        for (const auto& n : names) allowed += (allowed.empty() ? "" : ", ") + n;
        throw UsageError("--cmap " + name + " is not allowed: use one of " + allowed);
    }
    std::string fields;
    for (const SceneInfo& scene : scenes())
        if (!scene.colormap_keys.empty()) fields += std::string(fields.empty() ? "" : ", ") + scene.model;
    for (const SceneInfo& scene : scenes()) {
        if (scene.model != d.model) continue;
        if (scene.colormap_keys.empty()) break;
        for (const std::string& key : scene.colormap_keys) {
            d.style.insert_or_assign(key, name);
            const std::string colours = key.substr(0, key.size() - std::string("colormap").size()) + "colours";
            d.style.erase(colours);
            d.origins["style." + key] = "--cmap " + name;
        }
        return;
    }
    throw UsageError("--cmap: " + d.id + " (model " + d.model + ") draws no field to colour; the field models are " +
                     fields);
}

void render_figure(const Description& d, const OutputOptions& options, Progress& progress) {
    for (const SceneInfo& scene : scenes()) {
        if (scene.model != d.model) continue;
        std::error_code ec;
        std::filesystem::create_directories(options.dir, ec);
        if (ec || !std::filesystem::is_directory(options.dir))
            throw UsageError("--out " + options.dir.string() +
                             ": cannot create the folder: " + (ec ? ec.message() : "not a directory"));
        const FigureLock turn(options.dir, d.id);
        require_disk(d, options);
        require_memory(d, options, {});
        render::clear_font_cache();  // same pixels whatever was rendered before in this process
        // The figure's files replace the earlier ones together, once all are written.
        render::CommitGroup outputs;
        try {
            scene.render(d, options, progress);
        } catch (const KeyError& e) {
            throw UsageError(d.where(e.key) + ": " + e.what());
        } catch (const UsageError& e) {
            throw UsageError(located(d, e.what()));
        }
        outputs.commit();
        return;
    }
    std::string allowed;
    for (const SceneInfo& scene : scenes()) allowed += (allowed.empty() ? "" : ", ") + scene.model;
    throw UsageError(d.file.filename().string() + ": model \"" + d.model + "\" is unknown; allowed: " + allowed);
}

}  // namespace figures
