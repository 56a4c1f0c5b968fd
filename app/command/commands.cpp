#include "app/command/commands.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/command/describe.hpp"
#include "app/gallery/gallery.hpp"
#include "app/render/film_segments.hpp"
#include "app/render/formats.hpp"
#include "app/render/output_files.hpp"
#include "app/render/progress.hpp"
#include "app/render/render_figure.hpp"
#include "app/render/targets.hpp"
#include "app/work/cluster.hpp"
#include "app/work/schedule.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"
#include "description/integer_text.hpp"
#include "description/plain_name.hpp"
#include "ready/pattern.hpp"

namespace app {

void say(const char* kind, const std::string& message) {
    std::fprintf(stderr, "figgen: %s: %s\n", kind, description::printable(message).c_str());
}

namespace {

// CLI11's check that an option's text is an integer of [low, high] as
// description::integer_text reads it: applied to the text before CLI11
// converts it, so " 4" and "4294967297" are refused, never trimmed or wrapped.
CLI::Validator integer_in(long long low, long long high) {
    const std::string allowed = description::integers_allowed(low, high);  // as seed_option and threads_option say it
    return CLI::Validator(
        [=](std::string& text) {
            return description::integer_text(text, low, high)
                       ? std::string()
                       : description::printable(text, 40) + " is not allowed: use " + allowed;
        },
        "INT in [" + std::to_string(low) + " - " + std::to_string(high) + "]");
}

// --format's check of each name, in the words of the library's (output_options); its
// description, "{png,pdf,...}", is the one CLI::IsMember gave --help.
CLI::Validator format_in() {
    std::string listed;
    for (const std::string& n : format_names()) listed += (listed.empty() ? "" : ",") + n;
    return CLI::Validator(
        [](std::string& name) {
            const std::vector<std::string> names = format_names();
            return std::find(names.begin(), names.end(), name) != names.end()
                       ? std::string()
                       : description::printable(name, 40) + " is not allowed: use " + formats_allowed();
        },
        "{" + listed + "}");
}

// --max-memory, one option for every command that takes it; its value is read by parse_size.
void add_max_memory(CLI::App& command, std::string& size, const std::string& meaning) {
    command.add_option("--max-memory", size, meaning + " (e.g. 512M, 8G)")->capture_default_str();
}

}  // namespace

ListCommand::ListCommand(CLI::App& parent) {
    app = parent.add_subcommand("list", "List the figure ids and titles of the catalog");
}

int ListCommand::run() {
    for (const auto& file : description::catalog_files()) {
        const Description d = description::load_description(file);
        std::printf("%-20s %s\n", d.id.c_str(), d.title.c_str());
    }
    return 0;
}

ConvertCommand::ConvertCommand(CLI::App& parent) {
    app = parent.add_subcommand("convert", "Write a Ready pattern file (.vti) as the figgen description that runs it");
    app->add_option("pattern", pattern, "A 2-D Ready pattern file whose rule is a formula (.vti)")->required();
    app->add_option("--out", out_dir, "Write OUT/ID.toml (created if missing) instead of printing it");
}

int ConvertCommand::run() {
    if (ready::file_kind(pattern) != ready::FileKind::image)
        throw UsageError("pattern " + description::printable(pattern) +
                         " is not allowed: a Ready pattern file of an image, NAME.vti");
    const ready::Pattern converted = ready::read_pattern(pattern);
    // Checked as render would check it, from the same table: a formula
    // figgen cannot run is refused here, not when the description is
    // first rendered.
    const Description d = description::description_from_table(converted.description, pattern, converted.origins);
    description::at_source(d, [&] { return scenes::read_scene(d, scenes::SceneOptions{}); });
    const std::string text = ready::converted_text(converted, pattern);
    if (out_dir.empty()) {
        std::fputs(text.c_str(), stdout);
        return 0;
    }
    OutputOptions options;
    options.dir = out_dir;
    const base::Folder folder = open_output_folder(options);
    base::write_file_atomically(folder, converted.id + ".toml", text);
    std::printf("%s\n", description::printable((folder.path() / (converted.id + ".toml")).string()).c_str());
    return 0;
}

DescribeCommand::DescribeCommand(CLI::App& parent) {
    app = parent.add_subcommand("describe", "List a figure's settings: value, default, range, meaning");
    app->add_option("figure", target, "A figure id or .toml description file")->required();
}

int DescribeCommand::run() {
    std::fputs(describe(target).c_str(), stdout);
    return 0;
}

GalleryCommand::GalleryCommand(CLI::App& parent) {
    app = parent.add_subcommand("gallery", "Write DIR/index.html showing the figures rendered in DIR");
    app->add_option("--out", dir, "The folder of rendered figures")->capture_default_str();
    add_max_memory(*app, max_memory, "Decode no image whose header claims more than SIZE of memory: its card says why");
}

int GalleryCommand::run() {
    const std::uint64_t memory = parse_size("--max-memory", max_memory);
    if (!std::filesystem::is_directory(dir)) throw UsageError("--out " + dir + " is not a folder of rendered figures");
    const int shown = write_gallery(dir, memory);
    std::printf("%s/index.html: %d figures\n", dir.c_str(), shown);
    return 0;
}

ThumbnailsCommand::ThumbnailsCommand(CLI::App& parent) {
    app = parent.add_subcommand("thumbnails", "Write small copies of the figures rendered in a folder");
    app->add_option("--from", from, "The folder of rendered figures")->capture_default_str();
    app->add_option("--to", to, "Where the thumbnails go")->capture_default_str();
    app->add_option("--width", width, "Largest width in pixels")->capture_default_str()->check(integer_in(8, 2048));
    app->add_option("--height", height, "Largest height in pixels")->capture_default_str()->check(integer_in(8, 2048));
    add_max_memory(*app, max_memory,
                   "Decode no image whose header claims more than SIZE of memory: it is named and the others made");
}

int ThumbnailsCommand::run() {
    const std::uint64_t memory = parse_size("--max-memory", max_memory);
    if (!std::filesystem::is_directory(from))
        throw UsageError("--from " + from + " is not a folder of rendered figures");
    const ThumbnailsWritten made = write_thumbnails(from, to, width, height, memory);
    std::printf("%s: %d thumbnails\n", to.c_str(), made.written);
    if (made.refused.empty()) return 0;
    // Each file refused on a line of its own, the others written: the
    // README's grid would show an old thumbnail, so the run fails.
    for (const std::string& line : made.refused) say("error", line);
    return exit_usage_error;
}

RenderCommand::RenderCommand(CLI::App& parent, bool merge) {
    if (merge) {
        app = parent.add_subcommand("merge",
                                    "Draw figures from the parts of `figgen render --shard` runs (same options as "
                                    "render, and the same --set and --seed as the shards)");
        app->add_option("--from", from, "Parts folders (ID.parts), or the --out folders of the shards that hold them")
            ->required();
    } else {
        app = parent.add_subcommand("render", "Render figures by id or description file");
        app->add_option("--shard", shard,
                        "Compute only shard K of N of each figure's work items, into OUT/ID.parts, and draw "
                        "nothing (job arrays; then figgen merge)");
    }
    app->add_option("--schedule", schedule,
                    "Under mpirun: dynamic (the next item to whichever rank is free) or static (item i to rank i "
                    "mod N); the results are the same")
        ->capture_default_str()
        ->check(CLI::IsMember({"dynamic", "static"}));
    app->add_option("--threads", threads,
                    "Threads per process for work items, OpenMP and llvmpipe (1..1024; default: the cores, or "
                    "under mpirun the cores per rank of the node)")
        ->check(integer_in(1, 1024));
    app->add_option("--gl", gl,
                    "Where GL comes from: auto (EGL's surfaceless platform on llvmpipe, else OSMesa), osmesa, egl "
                    "(EGL surfaceless: llvmpipe, or the GPU Mesa finds) or egl-device (EGL's device platform: a "
                    "headless GPU; see --gl-device); default: FIGGEN_GL, else auto")
        ->capture_default_str();
    app->add_option("--gl-device", gl_device, "With --gl egl-device: which device (0.., in EGL's order)")
        ->capture_default_str()
        ->check(integer_in(0, 1023));
    app->add_option("figures", targets,
                    "Figure ids (see `figgen list`), .toml description files, or Ready's pattern files (.vti, .vtu)")
        ->required();
    app->add_option("--out", out_dir, "Output folder, created if missing")->capture_default_str();
    app->add_option("--set", overrides,
                    "Override a value: key=value for [params], section.key=value (style, figure, animation), or "
                    "id=NAME, title=TEXT");
    app->add_option("--seed", seed, "Seed of the random generator (0..2^63-1)")->check(integer_in(0, INT64_MAX));
    app->add_option("--scale", scale, "Scale every pixel size by X (0.1..8)")->capture_default_str();
    add_max_memory(*app, max_memory, "Refuse a figure whose estimated memory exceeds SIZE");
    app->add_option("--max-disk", max_disk, "Refuse a figure whose outputs would exceed SIZE (e.g. 100M, 8G)")
        ->capture_default_str();
    app->add_flag("--no-video", no_video, "Do not write the MP4 animation (as --format png)");
    app->add_flag("--frames", frames, "Also write the animation as a PNG sequence");
    app->add_option("--size", size, "The figure's size in pixels before --scale, WxH (e.g. 1200x600)");
    app->add_option("--fps", fps, "Frames per second of the animation (1..120)")->check(integer_in(1, 120));
    app->add_option("--cmap", cmap,
                    "Colormap of a field figure's fields: viridis, inferno, magma, plasma, cividis, Reds, Blues or "
                    "Greens");
    app->add_option("--format", formats, format_help())
        ->delimiter(',')
        ->check(format_in());
    app->add_flag("--transparent", transparent,
                  "Leave the figure's background out of the PNG, PDF and SVG: only the ink is opaque");
    app->add_flag("--strict", strict,
                  "Refuse a formula model whose timestep is past its explicit stability bound (else a warning)");
    app->add_flag("--error", error,
                  "Measure a formula model's error in time: run it again at half and a quarter of its timestep "
                  "(the metadata's and the gallery card's error)");
}

namespace {

int run_shards(const std::vector<CheckedFigure>& figures, const OutputOptions& options);
std::string distributable_ids();

}  // namespace

int RenderCommand::run() {
    OutputOptions options = output_options(*this);
    // Every figure's phase 1 first, so a mistake in the last one is reported
    // before minutes of rendering the first.
    std::vector<CheckedFigure> figures;
    for (const std::string& target : targets) figures.push_back(check_target(target, std::nullopt, *this, options));
    if (fps && std::none_of(figures.begin(), figures.end(),
                            [](const CheckedFigure& f) { return f.description->animation.has_value(); }))
        throw UsageError("--fps: none of the figures named has an animation");
    if (options.work.shard || options.work.merging())
        for (const CheckedFigure& f : figures)
            if (!f.scene->work())
                throw UsageError(std::string(options.work.shard ? "--shard" : "figgen merge") + ": " +
                                 f.description->id + " has no work items to share; allowed: " + distributable_ids());
    if (options.work.merging())
        for (const CheckedFigure& f : figures) check_merge_sources(*f.description, *f.scene->work(), options.work);
    // --gl, else FIGGEN_GL, else auto.
    std::string gl_from = "--gl " + gl;
    if (app->get_option("--gl")->count() == 0)
        if (const char* env = std::getenv("FIGGEN_GL"); env && *env) gl = env, gl_from = "FIGGEN_GL=" + gl;
    use_gl(*this, gl_from, !options.work.shard);  // a shard draws nothing
    apply_threads(*this, options.work.threads);
    if (options.work.shard) return run_shards(figures, options);
    // Under an MPI launcher, join the job now that every input is accepted:
    // rank 0 renders as a lone process would, the others run work items.
    std::unique_ptr<Cluster> cluster;
    if (launched_by_mpi()) {
        cluster = Cluster::join();
        options.work.cluster = cluster.get();
        if (cluster->rank() != 0) {
            for (const CheckedFigure& f : figures) {
                if (const scenes::WorkItems* items = f.scene->work()) {
                    serve_work(*f.description, *items, options.work);
                } else if (films_in_segments(*f.description, *f.scene, options)) {
                    WorkOptions one_at_a_time = options.work;
                    one_at_a_time.threads = 1;  // a process draws with one GL context
                    serve_work(*f.description, FilmSegments(*f.description, *f.scene, options), one_at_a_time);
                }
            }
            return 0;
        }
        try {
            ProgressBar progress = ProgressBar::for_stderr();
            render_all(figures, options, progress);
        } catch (const std::exception& e) {
            // The other ranks may wait for this one: end them all, the error said.
            const bool usage = dynamic_cast<const UsageError*>(&e) != nullptr;
            say(dynamic_cast<const InternalError*>(&e) ? "internal error" : "error", e.what());
            cluster->abort(usage ? exit_usage_error : exit_runtime_error);
        }
        return 0;
    }
    ProgressBar progress = ProgressBar::for_stderr();
    render_all(figures, options, progress);
    return 0;
}

namespace {

int run_shards(const std::vector<CheckedFigure>& figures, const OutputOptions& options) {
    const base::Folder folder = open_output_folder(options);
    ProgressBar progress = ProgressBar::for_stderr();
    for (const CheckedFigure& f : figures) {
        const int computed = run_shard(*f.description, *f.scene->work(), folder, options.work, progress);
        std::printf("%s: shard %d/%d: %d items computed into %s\n", f.description->id.c_str(), options.work.shard,
                    options.work.shards, computed,
                    description::printable((folder / parts_name(f.description->id)).string()).c_str());
    }
    return 0;
}

// The catalog's figures that have work items, for a message.
std::string distributable_ids() {
    std::string ids;
    for (const auto& file : description::catalog_files()) {
        const Description d = description::load_description(file);
        const auto scene = scenes::read_scene(d, {});
        if (scene->work()) ids += (ids.empty() ? "" : ", ") + d.id;
    }
    return ids;
}

}  // namespace

}  // namespace app
