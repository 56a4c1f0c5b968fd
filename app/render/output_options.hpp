#pragma once
// What a render writes and within which limits: the output folder, the
// scale, the formats chosen, the video's options, --max-memory and
// --max-disk, and how work items run.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <thread>

#include "app/work/schedule.hpp"
#include "description/description.hpp"
#include "media/video.hpp"
#include "scenes/scene.hpp"

namespace app {

using description::Description;
using description::UsageError;

struct OutputOptions {
    std::filesystem::path dir = "out";  // created if missing
    double scale = 1.0;                 // multiplies every size in pixels
    bool video = true;                  // write <id>.mp4
    bool frames = false;                // write <id>-frames/*.png
    bool webm = false;                  // write <id>.webm (VP9), made from the MP4 (kept only with `video`)
    std::set<std::string> chosen;       // the formats --format names that no flag above stands for (pdf, svg)
    bool vti = false;                   // write <id>.vti, a formula model's last step as Ready's file (--format vti)
    bool vtu = false;                   // write <id>.vtu, a mesh model's last step as Ready's file (--format vtu)
    bool formats_given = false;         // --format was given: a description's figure.formats is not used
    bool transparent = false;           // no background in the PNG, PDF and SVG
    bool strict = false;                // refuse a formula model's timestep past its stability bound (--strict)
    bool error = false;                 // measure a formula model's error in time (--error)
    media::VideoOptions video_options;
    // Limits on what one figure may need (--max-memory, --max-disk); a figure
    // whose estimate exceeds them is refused before anything is allocated.
    std::uint64_t max_memory = 4ull << 30;
    std::uint64_t max_disk = 4ull << 30;
    WorkOptions work;  // how work items run: threads, MPI, shards, merge

    bool animates() const { return video || webm || frames; }
    bool encodes() const { return video || webm; }  // an MP4 is encoded, kept or not
    // Which files a figure gets: app/render/formats.hpp's table.
    // Threads for the scenes' memory estimates: --threads, but never fewer
    // than the machine's cores, so that the estimate (kept in the JSON) is
    // the same for every run on this machine that uses no more threads than
    // cores, whatever its --threads or rank count.
    scenes::SceneOptions scene_options() const {
        return {scale, animates(), std::max(work.threads, static_cast<int>(std::thread::hardware_concurrency())),
                strict, error};
    }
};

}  // namespace app
