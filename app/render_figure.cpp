#include "app/render_figure.hpp"

#include <filesystem>
#include <system_error>

#include "app/figure_lock.hpp"
#include "render/atomic_file.hpp"
#include "render/text.hpp"

namespace app {

std::unique_ptr<scenes::Scene> check_figure(const Description& d, const OutputOptions& options) {
    auto scene = description::at_source(d, [&] { return scenes::read_scene(d, options.scene_options()); });
    require_disk(d, options);
    require_memory(d, options, scene->memory());
    return scene;
}

void render_figure(const Description& d, const scenes::Scene& scene, const OutputOptions& options,
                   scenes::Progress& progress) {
    std::error_code ec;
    std::filesystem::create_directories(options.dir, ec);
    if (ec || !std::filesystem::is_directory(options.dir))
        throw UsageError("--out " + options.dir.string() +
                         ": cannot create the folder: " + (ec ? ec.message() : "not a directory"));
    const FigureLock turn(options.dir, d.id);
    render::clear_font_cache();  // same pixels whatever was rendered before in this process
    // The figure's files replace the earlier ones together, once all are written.
    render::CommitGroup outputs;
    FigureFiles files(d, options, progress, estimate_memory(d, options, scene.memory()));
    scene.render(files);
    outputs.commit();
}

void render_figure(const Description& d, const OutputOptions& options, scenes::Progress& progress) {
    const auto scene = check_figure(d, options);
    render_figure(d, *scene, options, progress);
}

}  // namespace app
