// figgen: the command line. Lists the catalog and renders figures; all the
// work is in the figures library.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <optional>

#include "figures/catalog.hpp"
#include "figures/describe.hpp"
#include "figures/description.hpp"
#include "figures/gallery.hpp"
#include "figures/scene.hpp"
#include "figures/scene.hpp"
#include "figures/version.hpp"
#include "render/atomic_file.hpp"

namespace {

constexpr int exit_runtime_error = 1;  // a failure while running or writing
constexpr int exit_usage_error = 2;    // the command, a description or a value is wrong

int list_figures() {
    for (const auto& file : figures::catalog_files()) {
        const figures::Description d = figures::load_description(file);
        std::printf("%-20s %s\n", d.id.c_str(), d.title.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // First, before any thread starts: an interrupted render removes its
    // unfinished files and exits with 130 (SIGINT) or 143 (SIGTERM).
    render::remove_temporaries_on_signals();
    CLI::App app{"figgen: publication figures and animations of complex-systems models, headless."};
    app.set_version_flag("--version", figures::version());
    app.require_subcommand(1);

    CLI::App* list = app.add_subcommand("list", "List the figure ids and titles of the catalog");

    CLI::App* gallery = app.add_subcommand("gallery", "Write DIR/index.html showing the figures rendered in DIR");
    std::string gallery_dir = "out";
    gallery->add_option("--out", gallery_dir, "The folder of rendered figures")->capture_default_str();

    CLI::App* describe = app.add_subcommand("describe", "List a figure's settings: value, default, range, meaning");
    std::string describe_target;
    describe->add_option("figure", describe_target, "A figure id or .toml description file")->required();

    CLI::App* thumbs = app.add_subcommand("thumbnails", "Write small copies of the figures rendered in a folder");
    std::string thumbs_from = "out", thumbs_to = "docs/thumbs";
    int thumbs_width = 240, thumbs_height = 180;
    thumbs->add_option("--from", thumbs_from, "The folder of rendered figures")->capture_default_str();
    thumbs->add_option("--to", thumbs_to, "Where the thumbnails go")->capture_default_str();
    thumbs->add_option("--width", thumbs_width, "Largest width in pixels")->capture_default_str()->check(CLI::Range(8, 2048));
    thumbs->add_option("--height", thumbs_height, "Largest height in pixels")->capture_default_str()->check(CLI::Range(8, 2048));

    CLI::App* render = app.add_subcommand("render", "Render figures by id or description file");
    std::vector<std::string> targets;
    std::string out_dir = "out";
    std::vector<std::string> overrides;
    std::optional<std::uint64_t> seed;
    double scale = 1.0;
    bool no_video = false, frames = false;
    render->add_option("figures", targets, "Figure ids (see `figgen list`) or .toml description files")->required();
    render->add_option("--out", out_dir, "Output folder, created if missing")->capture_default_str();
    render->add_option("--set", overrides,
                       "Override a value: key=value for [params], or section.key=value (style, figure, animation)");
    render->add_option("--seed", seed, "Seed of the random generator (0..2^63-1)");
    render->add_option("--scale", scale, "Scale every pixel size by X (0.1..8)")->capture_default_str();
    std::uint64_t max_memory = 4ull << 30, max_disk = 4ull << 30;
    render->add_option("--max-memory", max_memory,
                       "Refuse a figure whose estimated memory exceeds SIZE (e.g. 512M, 8G)")
        ->transform(CLI::AsSizeValue(false))
        ->default_str("4G");
    render->add_option("--max-disk", max_disk, "Refuse a figure whose outputs would exceed SIZE (e.g. 100M, 8G)")
        ->transform(CLI::AsSizeValue(false))
        ->default_str("4G");
    render->add_flag("--no-video", no_video, "Do not write the MP4 animation (as --format png)");
    render->add_flag("--frames", frames, "Also write the animation as a PNG sequence");
    std::string size, cmap, format;
    std::optional<int> fps;
    render->add_option("--size", size, "The figure's size in pixels before --scale, WxH (e.g. 1200x600)");
    render->add_option("--fps", fps, "Frames per second of the animation (1..120)");
    render->add_option("--cmap", cmap,
                       "Colormap of a field figure's fields: viridis, inferno, magma, plasma, cividis, Reds, "
                       "Blues or Greens");
    render->add_option("--format", format,
                       "What to write besides the PNG and its JSON: png (nothing), mp4 (the animation, the "
                       "default) or frames (the animation as a PNG sequence)")
        ->check(CLI::IsMember({"png", "mp4", "frames"}));

    // CLI11 would only say that a subcommand is required.
    const std::vector<CLI::App*> commands = {list, describe, gallery, thumbs, render};
    if (argc > 1 && argv[1][0] != '-' &&
        std::none_of(commands.begin(), commands.end(), [&](const CLI::App* c) { return c->get_name() == argv[1]; })) {
        std::string allowed;
        for (const CLI::App* command : commands) allowed += (allowed.empty() ? "" : ", ") + command->get_name();
        std::fprintf(stderr, "figgen: error: unknown command '%s'; allowed: %s; see figgen --help\n", argv[1],
                     allowed.c_str());
        return exit_usage_error;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "figgen: error: %s; see figgen --help\n", e.what());
        return exit_usage_error;
    }

    try {
        if (*list) return list_figures();
        if (*describe) {
            std::fputs(figures::describe(figures::resolve_figure(describe_target)).c_str(), stdout);
            return 0;
        }
        if (*thumbs) {
            if (!std::filesystem::is_directory(thumbs_from)) {
                std::fprintf(stderr, "figgen: error: --from %s is not a folder of rendered figures\n",
                             thumbs_from.c_str());
                return exit_usage_error;
            }
            const int written = figures::write_thumbnails(thumbs_from, thumbs_to, thumbs_width, thumbs_height);
            std::printf("%s: %d thumbnails\n", thumbs_to.c_str(), written);
            return 0;
        }
        if (*gallery) {
            if (!std::filesystem::is_directory(gallery_dir)) {
                std::fprintf(stderr, "figgen: error: --out %s is not a folder of rendered figures\n",
                             gallery_dir.c_str());
                return exit_usage_error;
            }
            const int shown = figures::write_gallery(gallery_dir);
            std::printf("%s/index.html: %d figures\n", gallery_dir.c_str(), shown);
            return 0;
        }

        if (!(scale >= 0.1 && scale <= 8.0)) {  // also false for NaN
            std::fprintf(stderr, "figgen: error: --scale %g is not allowed: use a number from 0.1 to 8\n", scale);
            return exit_usage_error;
        }
        if (seed && *seed > static_cast<std::uint64_t>(INT64_MAX)) {
            std::fprintf(stderr, "figgen: error: --seed is not allowed: use 0..2^63-1\n");
            return exit_usage_error;
        }
        if (!format.empty() && (no_video || frames)) {
            std::fprintf(stderr, "figgen: error: --format %s is not allowed with --no-video or --frames: use one\n",
                         format.c_str());
            return exit_usage_error;
        }
        if (format == "png") no_video = true;
        if (format == "frames") no_video = true, frames = true;
        if (!size.empty()) {
            int w = 0, h = 0;
            char rest = 0;
            if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &rest) != 2 || w < 2 || h < 2 || w > 16384 ||
                h > 16384) {
                std::fprintf(stderr,
                             "figgen: error: --size %s is not allowed: use WIDTHxHEIGHT, each 2..16384, e.g. "
                             "1200x600\n",
                             size.c_str());
                return exit_usage_error;
            }
            overrides.push_back("figure.size=[" + std::to_string(w) + "," + std::to_string(h) + "]");
        }
        if (fps && !(*fps >= 1 && *fps <= 120)) {
            std::fprintf(stderr, "figgen: error: --fps %d is not allowed: use 1..120 frames per second\n", *fps);
            return exit_usage_error;
        }
        figures::OutputOptions options;
        options.dir = out_dir;
        options.scale = scale;
        options.video = !no_video;
        options.frames = frames;
        options.max_memory = max_memory;
        options.max_disk = max_disk;
        // Load every description first, so a typo in the last one fails before
        // minutes of rendering the first.
        std::vector<figures::Description> descriptions;
        for (const std::string& target : targets) {
            figures::Description d = figures::load_description(figures::resolve_figure(target), overrides, seed);
            if (!cmap.empty()) figures::apply_colormap(d, cmap);
            if (fps && d.animation) d.animation->fps = *fps;
            descriptions.push_back(std::move(d));
        }
        if (fps && std::none_of(descriptions.begin(), descriptions.end(),
                                [](const figures::Description& d) { return d.animation.has_value(); })) {
            std::fprintf(stderr, "figgen: error: --fps: none of the figures named has an animation\n");
            return exit_usage_error;
        }
        figures::Progress progress = figures::Progress::for_stderr();
        for (const auto& d : descriptions) figures::render_figure(d, options, progress);
        return 0;
    } catch (const figures::UsageError& e) {
        std::fprintf(stderr, "figgen: error: %s\n", e.what());
        return exit_usage_error;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "figgen: error: %s\n", e.what());
        return exit_runtime_error;
    }
}
