#include "app/command/library.hpp"

#include <mutex>

#include "app/render/formats.hpp"
#include "description/catalog.hpp"

namespace app {
namespace {

// The GL platform of this process's first render: its one GL context.
std::optional<std::string> gl_in_use;
std::mutex gl_lock;

}  // namespace

RenderResult render_request(const RenderRequest& request, scenes::Progress& progress) {
    const RenderSettings& s = request.settings;
    if (!s.shard.empty() || !s.from.empty())
        throw UsageError("shards and merges are the command's: use figgen render --shard and figgen merge");
    const OutputOptions options = output_options(s);
    std::vector<CheckedFigure> figures;
    figures.push_back(check_target(request.target, request.text, s, options));
    const description::Description& d = *figures.front().description;
    {
        std::lock_guard<std::mutex> hold(gl_lock);
        use_gl(s, "gl=" + s.gl, false);  // a platform figgen knows
        if (gl_in_use && *gl_in_use != s.gl)
            throw OptionError("--gl", s.gl, *gl_in_use, "gl=" + s.gl,
                              " is not allowed: this process draws with gl=" + *gl_in_use +
                                  " since its first render (one GL context a process)");
        if (!gl_in_use) {
            use_gl(s, "gl=" + s.gl);
            apply_threads(s, options.work.threads);
            gl_in_use = s.gl;
        }
    }
    render_all(figures, options, progress);
    RenderResult result{d.id, options.dir / (d.id + ".json"), {}};
    for (const OutputFormat& format : output_formats()) {
        if (!format.wanted(d, options)) continue;
        const std::filesystem::path file = options.dir / (d.id + format.suffix);
        if (std::filesystem::exists(file)) result.files.push_back(file);
    }
    return result;
}

Described describe_request(const std::string& target, const std::optional<std::string>& text) {
    if (!text) return describe_figure(target);
    description::SettingsLog top;  // the description's own sections, read as it is parsed
    const description::Description d = description::parse_description(*text, target);
    return describe_figure(d, top.sections);
}

}  // namespace app
