#pragma once
// What `figgen render` (and merge) and the Python module's render() share:
// the render options, and the steps from them to written figures.

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/render/output_files.hpp"
#include "description/description.hpp"
#include "scenes/output.hpp"
#include "scenes/scene.hpp"

namespace app {

// What can only be a bug in figgen (a broken invariant), reported as
// "internal error" with where it happened; exit status 1.
struct InternalError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// "512M", "8G", "1.5GiB", "4096": bytes (K, M, G, T, P are powers of 1024; a
// trailing "B" or "iB" is allowed). UsageError naming `option` unless it is
// a size from 1 byte to 1 PiB.
std::uint64_t parse_size(const std::string& option, const std::string& text);

// figgen render's options (docs/commands.md), as the command line or Python gives them.
struct RenderSettings {
    std::vector<std::string> overrides, from;  // --set; merge's --from
    std::string shard, schedule = "dynamic";
    std::optional<int> threads;
    std::string gl = "auto";  // --gl, FIGGEN_GL
    int gl_device = 0;
    std::string out_dir = "out", size, cmap;
    std::vector<std::string> formats;  // --format, split at commas
    std::optional<std::uint64_t> seed;
    std::optional<int> fps;
    double scale = 1.0;
    bool no_video = false, frames = false, transparent = false, strict = false, error = false;
    std::string max_memory = "4G", max_disk = "4G";  // sizes, read by parse_size
};

// A render option refused: the command's message, `named` + `rest`
// ("--scale 0" + " is not allowed: use a number from 0.1 to 8"), and its
// parts, for a caller that names options its own way (Python's arguments).
struct OptionError : description::UsageError {
    OptionError(std::string option, std::string value, std::string allowed, const std::string& named,
                std::string rest);
    std::string option;   // "--scale"
    std::string value;    // as given, printable
    std::string allowed;  // "a number from 0.1 to 8"
    std::string rest;     // the message after the option and its value
};

// --seed's and --threads's text, checked as the command line checks them; OptionError if not allowed.
std::uint64_t seed_option(const std::string& text);
int threads_option(const std::string& text);

// The settings as output options; OptionError (a UsageError) for a value out of range.
OutputOptions output_options(const RenderSettings& s);

// A figure read and checked (phase 1): its description and its scene.
struct CheckedFigure {
    std::unique_ptr<description::Description> description;  // the scene refers to it: kept in place
    std::unique_ptr<scenes::Scene> scene;
};

// Reads `target` (a catalog id, a description or a Ready pattern file; or,
// given `text`, that description, named `target`) with the settings'
// --set, --size, --seed, --cmap and --fps, and checks it against `options`.
CheckedFigure check_target(const std::string& target, const std::optional<std::string>& text, const RenderSettings& s,
                           const OutputOptions& options);

// Checks the GL platform `s.gl` names and, with `take`, takes it for this
// process (`given`: how the user named it, for messages: "--gl egl",
// "FIGGEN_GL=egl"); UsageError for one not allowed here.
void use_gl(const RenderSettings& s, const std::string& given, bool take = true);

// --threads (or `threads`) for OpenMP and llvmpipe, before GL starts.
void apply_threads(const RenderSettings& s, int threads);

// Phases 2 and 3 of checked figures, into options.dir, reporting to
// `progress`; a failure says which figure and how far its run got.
void render_all(const std::vector<CheckedFigure>& figures, const OutputOptions& options, scenes::Progress& progress);

}  // namespace app
