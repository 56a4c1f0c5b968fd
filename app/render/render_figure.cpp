#include "app/render/render_figure.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "app/render/film_segments.hpp"
#include "app/render/render_settings.hpp"
#include "app/work/figure_lock.hpp"
#include "base/atomic_file.hpp"
#include "render/text.hpp"

namespace app {

std::unique_ptr<scenes::Scene> check_figure(const Description& d, const OutputOptions& options) {
    auto scene = description::at_source(d, [&] { return scenes::read_scene(d, options.scene_options()); });
    const scenes::WorkItems* items = scene->work();
    require_disk(d, options, items && !options.work.merging() ? items->total_bytes() : 0.0);
    require_memory(d, options, scene->memory());
    return scene;
}

base::Folder open_output_folder(const OutputOptions& options) {
    try {
        base::Folder folder(options.dir, true);
        if (::faccessat(folder.fd(), ".", W_OK | X_OK, AT_EACCESS) != 0)
            throw std::runtime_error("cannot write there: " + std::string(std::strerror(errno)));
        return folder;
    } catch (const std::runtime_error& e) {
        const std::string dir = options.dir.string();
        throw OptionError("--out", dir, "a folder figgen can write", "--out " + dir,
                          std::string(": ") + e.what() + "; allowed: a folder figgen can write");
    }
}

void render_figure(const Description& d, const scenes::Scene& scene, const base::Folder& folder,
                   const OutputOptions& options, scenes::Progress& progress) {
    const FigureLock turn(folder, d.id);
    // Holding the turn, no live process writes this figure here: any
    // temporaries of its files are a killed process's.
    base::remove_stale_temporaries(folder, output_names(d.id));
    render::clear_font_cache();  // same pixels whatever was rendered before in this process
    // The figure's files replace the earlier ones together, once all are written.
    base::CommitGroup outputs;
    // Under mpirun, the film's segments from every rank first (rank 0 takes
    // its share), then the figure's own run, which draws no frame.
    std::optional<std::vector<nlohmann::json>> segments;
    const bool film_in_segments = films_in_segments(d, scene, options);
    if (film_in_segments) {
        WorkOptions one_at_a_time = options.work;
        one_at_a_time.threads = 1;  // a process draws with one GL context
        segments = run_work(d, FilmSegments(d, scene, options), folder, one_at_a_time, progress);
    }
    FigureFiles files(d, options, folder, progress, estimate_memory(d, options, scene.memory()),
                      segments ? &*segments : nullptr);
    description::at_source(d, [&] { scene.render(files); });  // a setting refused at draw time names its line
    outputs.commit();
    // The figure is in place: the parts of its items are no longer needed
    // (a merge's came from elsewhere and are left as they are).
    if ((scene.work() || film_in_segments) && !options.work.merging()) remove_parts(folder, d.id);
}

void render_figure(const Description& d, const OutputOptions& options, scenes::Progress& progress) {
    const auto scene = check_figure(d, options);
    render_figure(d, *scene, open_output_folder(options), options, progress);
}

}  // namespace app
