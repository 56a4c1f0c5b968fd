#include "app/render/render_settings.hpp"

#include <sched.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdlib>
#include <thread>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "app/render/formats.hpp"
#include "app/render/progress.hpp"
#include "app/render/render_figure.hpp"
#include "app/render/targets.hpp"
#include "app/work/cluster.hpp"
#include "description/catalog.hpp"
#include "description/integer_text.hpp"
#include "description/plain_name.hpp"
#include "media/media.hpp"
#include "ready/pattern.hpp"
#include "render/gl/gl_context.hpp"
#include "render/vector/vector.hpp"
#include "sim/check.hpp"

namespace app {

std::uint64_t parse_size(const std::string& option, const std::string& text) {
    const UsageError refused(option + " " + text +
                             " is not allowed: use a size from 1 byte to 1 PiB, e.g. 512M, 8G or 1.5G");
    if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '.')) throw refused;
    double number = 0.0;
    std::size_t used = 0;
    try {
        number = std::stod(text, &used);
    } catch (const std::exception&) {
        throw refused;
    }
    // The unit: none or B, else K, M, G, T or P, each with an optional B or iB.
    std::string unit = text.substr(used);
    for (char& ch : unit) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    for (const char* suffix : {"IB", "B"})
        if (unit.size() > std::strlen(suffix) &&
            unit.compare(unit.size() - std::strlen(suffix), std::string::npos, suffix) == 0) {
            unit.resize(unit.size() - std::strlen(suffix));
            break;
        }
    static const std::string units = "KMGTP";
    if (unit == "B") unit.clear();
    if (unit.size() > 1 || (unit.size() == 1 && units.find(unit[0]) == std::string::npos)) throw refused;
    const double power = unit.empty() ? 0.0 : static_cast<double>(units.find(unit[0]) + 1);
    const double bytes = std::floor(number * std::pow(1024.0, power));
    if (!(bytes >= 1.0 && bytes <= std::pow(1024.0, 5))) throw refused;  // also NaN and infinity
    return static_cast<std::uint64_t>(bytes);
}

namespace {

// Threads for a process by default: the cores it may run on (its affinity
// mask: mpirun binds a rank to a core, or to the cores --map-by gives it),
// shared with the other ranks on its node when it is not bound.
int default_threads() {
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    cpu_set_t mask;
    CPU_ZERO(&mask);
    const int allowed = ::sched_getaffinity(0, sizeof mask, &mask) == 0 ? CPU_COUNT(&mask) : cores;
    if (allowed < cores) return std::max(1, allowed);  // bound: it has these to itself
    return std::max(1, cores / launcher_local_size());
}

// "--scale 0 is not allowed: use a number from 0.1 to 8"; `separator`: ": " as CLI11's checks say it.
OptionError not_allowed(const std::string& option, const std::string& value, const std::string& allowed,
                        const char* separator = " ") {
    return OptionError(option, value, allowed, option + separator + value, " is not allowed: use " + allowed);
}

// An integer option's text as CLI11's check in commands.cpp reads it (description::integer_text).
long long integer_option(const std::string& option, const std::string& text, long long low, long long high) {
    const std::optional<long long> value = description::integer_text(text, low, high);
    if (!value)
        throw not_allowed(option, description::printable(text, 40), description::integers_allowed(low, high), ": ");
    return *value;
}

}  // namespace

OptionError::OptionError(std::string option_, std::string value_, std::string allowed_, const std::string& named,
                         std::string rest_)
    : UsageError(named + rest_),
      option(std::move(option_)),
      value(std::move(value_)),
      allowed(std::move(allowed_)),
      rest(std::move(rest_)) {}

std::uint64_t seed_option(const std::string& text) {
    return static_cast<std::uint64_t>(integer_option("--seed", text, 0, INT64_MAX));
}

int threads_option(const std::string& text) {
    return static_cast<int>(integer_option("--threads", text, 1, 1024));
}

// The options of `figgen render` as output options; OptionError for a value out of range.
OutputOptions output_options(const RenderSettings& c) {
    if (!(c.scale >= 0.1 && c.scale <= 8.0))  // also false for NaN
        throw not_allowed("--scale", description::shown(c.scale), description::numbers_allowed(0.1, 8));
    std::string formats;
    for (const std::string& f : c.formats) formats += (formats.empty() ? "" : ",") + f;
    if (!c.formats.empty() && (c.no_video || c.frames))
        throw UsageError("--format " + formats + " is not allowed with --no-video or --frames: use one");
    if (c.out_dir.empty())
        throw OptionError("--out", "", "a folder", "--out",
                          " is empty: give the folder the figures go into, e.g. --out out");
    OutputOptions options;
    options.dir = c.out_dir;
    options.scale = c.scale;
    options.video = c.formats.empty() && !c.no_video;
    options.frames = c.frames;
    options.formats_given = !c.formats.empty();
    // --format's check (format_names) let through only names the table chooses by.
    for (const std::string& name : c.formats) {
        const OutputFormat* format = output_format(name);
        if (!format || !format->choose)  // the command line's check lets none through; a library call's may
            throw not_allowed("--format", description::printable(name, 40), formats_allowed(), ": ");
        format->choose(options);
    }
    options.transparent = c.transparent;
    options.strict = c.strict;
    options.error = c.error;
    options.max_memory = parse_size("--max-memory", c.max_memory);
    options.max_disk = parse_size("--max-disk", c.max_disk);
    if (c.threads && (*c.threads < 1 || *c.threads > 1024))
        throw not_allowed("--threads", std::to_string(*c.threads), description::integers_allowed(1, 1024), ": ");
    options.work.threads = c.threads.value_or(default_threads());
    options.work.schedule = c.schedule == "static" ? Schedule::fixed : Schedule::dynamic;
    for (const std::string& from : c.from) options.work.merge_from.emplace_back(from);
    if (!c.shard.empty()) {
        const std::size_t slash = c.shard.find('/');
        const std::optional<long long> n = slash == std::string::npos
                                               ? std::nullopt
                                               : description::integer_text(c.shard.substr(slash + 1), 1, 1000000);
        const std::optional<long long> k =
            n ? description::integer_text(c.shard.substr(0, slash), 1, *n) : std::nullopt;
        if (!k)
            throw UsageError("--shard " + description::printable(c.shard, 40) +
                             " is not allowed: use K/N with 1 <= K <= N <= 1000000, two integers, e.g. 2/8");
        options.work.shard = static_cast<int>(*k);
        options.work.shards = static_cast<int>(*n);
        if (launched_by_mpi())
            throw UsageError("--shard " + description::printable(c.shard, 40) +
                             " is not allowed under mpirun: use one or the other");
    }
    if (!c.from.empty() && launched_by_mpi())
        throw UsageError("figgen merge is not allowed under mpirun: run it as one process");
    return options;
}

// --threads (or the default) for OpenMP and, unless the user set
// LP_NUM_THREADS, llvmpipe; before any thread or GL library starts.
void apply_threads(const RenderSettings& c, int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    if (c.threads || launched_by_mpi()) ::setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 0);
}

// The --set assignments, with --size as one more.
namespace {

std::vector<std::string> overrides_of(const RenderSettings& c) {
    std::vector<std::string> overrides = c.overrides;
    if (c.size.empty()) return overrides;
    const std::size_t x = c.size.find('x');
    const std::optional<long long> w =
        x == std::string::npos ? std::nullopt : description::integer_text(c.size.substr(0, x), 2, 16384);
    const std::optional<long long> h = w ? description::integer_text(c.size.substr(x + 1), 2, 16384) : std::nullopt;
    if (!h)
        throw not_allowed("--size", description::printable(c.size, 40), "WIDTHxHEIGHT, each 2..16384, e.g. 1200x600");
    overrides.push_back("figure.size=[" + std::to_string(*w) + "," + std::to_string(*h) + "]");
    return overrides;
}

// Renders a checked figure; what can only be a bug, or memory running out,
// becomes a one-line error saying which figure and how far its run got.
void render_reporting(const Description& d, const scenes::Scene& scene, const base::Folder& folder,
                      const OutputOptions& options, scenes::Progress& to) {
    ProgressTally progress(to);
    try {
        render_figure(d, scene, folder, options, progress);
    } catch (const std::bad_alloc&) {
        throw std::runtime_error(d.id + ": out of memory (" + progress.position() + "); its estimate was " +
                                 format_bytes(estimate_memory(d, options, scene.memory()).bytes) +
                                 ", so the machine had less free than that: free some, or make it smaller");
    } catch (const sim::ParameterError&) {
        throw;  // a model's refusal at run time: a run failure with its own message
    } catch (const std::logic_error& e) {
        throw InternalError(d.id + " (" + progress.position() + "): " + e.what());
    }
}

}  // namespace

CheckedFigure check_target(const std::string& target, const std::optional<std::string>& text, const RenderSettings& s,
                           const OutputOptions& options) {
    const std::vector<std::string> assignments = overrides_of(s);
    auto d = std::make_unique<Description>(
        text ? description::parse_description(*text, target, assignments, s.seed)
        : load_target(target, assignments, s.seed, false));
    if (options.vti && !scenes::extra_file(*d, "vti"))
        throw UsageError("--format vti: " + d->id + " is a " + d->scene +
                         " figure; the scenes that write a VTI file are " + scenes::scenes_writing("vti"));
    if (options.vtu && !scenes::extra_file(*d, "vtu"))
        throw UsageError("--format vtu: " + d->id + " is a " + d->scene +
                         " figure; the scenes that write a VTU file are " + scenes::scenes_writing("vtu"));
    if (!s.cmap.empty()) scenes::apply_colormap(*d, s.cmap);
    if (s.fps && d->animation) d->animation->fps = *s.fps;
    auto scene = check_figure(*d, options);
    // A pattern's stored arrays, decoded once its figure and its memory
    // estimate (which counts them) have passed; the scene holds `*d`.
    if (!text && ready::file_kind(target) == ready::FileKind::image) ready::decode_stored_start(*d);
    scene->check_run();
    return {std::move(d), std::move(scene)};
}

void use_gl(const RenderSettings& s, const std::string& given, bool take) {
    if (!render::gl_platform_of(s.gl)) {
        const std::string allowed = render::gl_platforms_allowed();
        throw OptionError("--gl", description::printable(s.gl, 40), allowed, given, " is not allowed: use " + allowed);
    }
    if (s.gl_device != 0 && s.gl != "egl-device")
        throw UsageError("--gl-device " + std::to_string(s.gl_device) + " is not allowed with " + given +
                         ": use it with --gl egl-device");
    if (!take) return;
    const render::GlChoice choice{*render::gl_platform_of(s.gl), s.gl_device};
    if (const std::optional<std::string> refused = render::check_gl_choice(choice)) throw UsageError(*refused);
    render::choose_gl(choice);
}

void render_all(const std::vector<CheckedFigure>& figures, const OutputOptions& options, scenes::Progress& progress) {
    const base::Folder folder = open_output_folder(options);
    // Every input is accepted and drawing will follow: open the GL library
    // while the first model runs.
    render::preload_gl();
    // And FFmpeg's module when a film will be encoded.
    if (options.encodes() && std::any_of(figures.begin(), figures.end(),
                                         [](const CheckedFigure& f) { return f.description->animation.has_value(); }))
        media::codec::preload();
    // And cairo's when a figure is written as PDF or SVG.
    if (std::any_of(figures.begin(), figures.end(),
                    [&](const CheckedFigure& f) { return writes_vector(*f.description, options); }))
        render::vector::preload();
    for (const CheckedFigure& f : figures) render_reporting(*f.description, *f.scene, folder, options, progress);
}

}  // namespace app
