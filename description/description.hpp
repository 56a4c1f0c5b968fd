#pragma once
// A figure description: one TOML file under figures/ saying what to draw.
//
//   id, title, source, scene, seed, caption      top-level keys
//   original_caption, language                   the printed caption and its language
//                                                (`model` is read as an old name of `scene`)
//   [params]     the model's parameters (checked by its scene)
//   [style]      drawing options (checked by its scene)
//   [figure]     panels = [steps...], size = [w, h], panel_title = "step {step}", columns,
//                caption = "none" | "title" | "original" (drawn beneath the figure)
//   [animation]  steps = [first, last], stride, fps, size = [w, h], title,
//                poster = step (the frame a player shows before it plays)
//
// Values given on the command line (--set key=value, --seed) are written
// into the table before it is read, so they pass the same checks.

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "description/settings.hpp"

namespace description {

struct StoredStart;  // description/stored_start.hpp
struct StoredMesh;   // description/stored_mesh.hpp

struct Animation {
    int first = 0;                      // first step shown
    int last = 0;                       // last step shown
    int stride = 1;                     // steps between frames
    int fps = 30;                       // frames per second
    int width = 640, height = 640;      // pixels at scale 1
    std::string title = "step {step}";  // drawn above the frame; {step} is the true step
    // Frames per film segment: each is encoded on its own, from a key frame,
    // and the segments are joined by stream copy, so a film made in segments
    // on many processes or threads is the same film (0: one segment). 60
    // frames, 2 s at 30 fps: measured on five catalog films (docs/speed.md,
    // Films), their MP4s are 5 to 22% larger than with 120 and 1.16
    // to 1.79 times a single stream's, and twice as many segments (5 to 7)
    // can be encoded at once; 30 would make them 16 to 65% larger than 120.
    int segment_frames = 60;
    // The step whose frame is the film's poster (the still a player shows
    // before it plays, HTML's poster): a step from first to last; the frame
    // at that step or, as ffmpeg's -ss seeks, the last one before it. None:
    // the last frame.
    std::optional<int> poster = std::nullopt;
    // Frames after the run's that turn the camera once around the last
    // step (a 3-D scene's; 0: none). The k-th of n looks from k + 1 n-ths
    // of a turn on, so the last is the run's own view again.
    int turn_frames = 0;
    // The frames of the run: at first, first + stride, ... up to last.
    int run_frames() const { return (last - first) / stride + 1; }
    int frame_count() const { return run_frames() + turn_frames; }
    bool shows(int step) const { return step >= first && step <= last && (step - first) % stride == 0; }
};

struct Description {
    std::filesystem::path file;     // where it was read from
    std::string id;                 // e.g. "tc7-1": the output files' names
    std::string title;              // one line, for `figgen list`
    std::string source;             // the printed figure it reproduces
    std::string scene;              // which scene draws it, e.g. "gray_scott", "roughness"
    std::string caption;            // decisions and notes, copied into the metadata
    std::string original_caption;   // the printed figure's own caption, in the document's language
    std::string language;           // that language, a fontconfig tag ("zh-cn", "ja"); empty: not given
    std::uint64_t seed = 0;         // for the project's generator
    toml::table params;             // [params], read by the scene through Settings
    toml::table style;              // [style], likewise
    std::vector<int> panels;        // steps of the figure's panels, ascending
    int width = 900, height = 450;  // figure size in pixels at scale 1
    std::string panel_title = "step {step}";
    int columns = 0;                // panels a row ([figure] columns); 0: chosen for the figure's size
    std::string figure_caption = "none";  // drawn beneath the figure: "none", "title" or "original"
    std::vector<std::string> formats;  // vector files the figure asks for: "pdf", "svg" (--format overrides)
    std::optional<Animation> animation;
    // Where each key was given: "section.key" (top-level keys under
    // "description.") -> "tc7-1.toml:7" or "--set r=0.5".
    std::map<std::string, std::string> origins;
    // The arrays a model starts from, from a Ready pattern file that stores
    // them (figgen render PATTERN.vti); null for a description file, which
    // cannot name a file to read.
    std::shared_ptr<const StoredStart> stored_start;
    // The mesh of a Ready .vtu pattern (description/stored_mesh.hpp).
    std::shared_ptr<const StoredMesh> stored_mesh;

    // Where `key` ("params.n", "params.plants[1].axiom") was given: its file
    // and line, the --set that gave it, or else just the file.
    std::string where(const std::string& key) const;

    // The last step any output needs: the model never runs past it.
    int last_step(bool with_animation) const;
};

// The one place a SettingError meets the description it came from: runs
// `read` and throws its SettingError again, its message beginning with
// where its key was given (d.where). Every reader of descriptions goes through it.
template <class Read>
auto at_source(const Description& d, Read&& read) -> decltype(read()) {
    try {
        return read();
    } catch (const SettingError& e) {
        if (!e.where().empty()) throw;
        throw e.at(d.where(e.key()));
    }
}

// The largest width or height a figure may have, pixels ([figure] size,
// [animation] size, --size): a size a message suggests is never larger.
inline constexpr int max_figure_side = 16384;

// The largest description file read; a larger one is refused before it is parsed.
inline constexpr std::size_t max_description_bytes = 16u << 20;

// Reads `file`, applies `overrides` ("key=value"; a bare key means params.key,
// except id and title, the figure's own)
// and `seed` if given. Throws UsageError naming the file, key and what is allowed.
Description load_description(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                             std::optional<std::uint64_t> seed = std::nullopt);

// The same from the description's text; `file` names it in messages.
Description parse_description(std::string_view text, const std::filesystem::path& file,
                              const std::vector<std::string>& overrides = {},
                              std::optional<std::uint64_t> seed = std::nullopt);
// The same from a table made as data (a Ready pattern, ready/pattern.hpp):
// `origins` says where each key ("params.k", as Description::origins) was
// given, e.g. "P.vti <param name=\"k\">".
Description description_from_table(toml::table root, const std::filesystem::path& file,
                                   std::map<std::string, std::string> origins,
                                   const std::vector<std::string>& overrides = {},
                                   std::optional<std::uint64_t> seed = std::nullopt);
// Writes one --set assignment ("key=value", "section.key=value") into a
// description's table; throws UsageError for a malformed one.
void apply_override(toml::table& root, const std::string& assignment);

// `pattern` with each {name} replaced by its value, e.g. "rule {rule}, step {step}".
std::string expand(const std::string& pattern, const std::vector<std::pair<std::string, std::string>>& values);
// "step {step}" with {step} replaced.
std::string format_step(const std::string& pattern, int step);

}  // namespace description
