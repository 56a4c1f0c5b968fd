#pragma once
// What a figure writes into the output folder, all through temporary names:
//   <id>.png            the panels, with id, seed and parameters in tEXt chunks
//   <id>.mp4            the animation, streamed frame by frame
//   <id>.webp           its short looping preview (animated WebP), with the MP4
//   <id>.webm           the film as VP9 in WebM, for the web (--format webm)
//   <id>.pdf, <id>.svg  the figure as vector graphics (--format pdf, svg)
//   <id>.vti            a formula model's last step as Ready's file (--format vti)
//   <id>-frames/NNNNN.png  the same frames as a PNG sequence (--frames)
//   <id>.json           metadata of all of them: parameters, seed, per-panel
//                       step, statistics and state hash, frame list

#include <algorithm>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "app/frame_pipe.hpp"
#include "app/segment_encoders.hpp"
#include "app/schedule.hpp"
#include "description/description.hpp"
#include "base/atomic_file.hpp"
#include "render/image.hpp"
#include "media/video.hpp"
#include "scenes/output.hpp"
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
    bool formats_given = false;         // --format was given: a description's figure.formats is not used
    bool transparent = false;           // no background in the PNG, PDF and SVG
    render::VideoOptions video_options;
    // Limits on what one figure may need (--max-memory, --max-disk); a figure
    // whose estimate exceeds them is refused before anything is allocated.
    std::uint64_t max_memory = 4ull << 30;
    std::uint64_t max_disk = 4ull << 30;
    WorkOptions work;  // how work items run: threads, MPI, shards, merge

    bool animates() const { return video || webm || frames; }
    bool encodes() const { return video || webm; }  // an MP4 is encoded, kept or not
    // Which files a figure gets: app/formats.hpp's table.
    // Threads for the scenes' memory estimates: --threads, but never fewer
    // than the machine's cores, so that the estimate (kept in the JSON) is
    // the same for every run on this machine that uses no more threads than
    // cores, whatever its --threads or rank count.
    scenes::SceneOptions scene_options() const {
        return {scale, animates(), std::max(work.threads, static_cast<int>(std::thread::hardware_concurrency()))};
    }
};

// The figure's size in pixels at the output scale.
int figure_width(const Description& d, const OutputOptions& options);
int figure_height(const Description& d, const OutputOptions& options);

// A figure's estimated peak memory: the model's `needs` (the scene's
// phase-1 estimate) plus the images it draws (figure, frames, encoder).
struct MemoryEstimate {
    double bytes = 0.0;
    scenes::MemoryNeed largest;
    // The film's segments encoded at once (app/segment_encoders.hpp): one
    // a core, at most one a segment, fewer where --max-memory would not
    // hold them; counted in `bytes`.
    int film_encoders = 1;
};
MemoryEstimate estimate_memory(const Description& d, const OutputOptions& options,
                               const std::vector<scenes::MemoryNeed>& needs);
// Refuses (UsageError) a figure whose estimate exceeds options.max_memory;
// the message gives the estimate and its largest part. Returns the estimate.
MemoryEstimate require_memory(const Description& d, const OutputOptions& options,
                              const std::vector<scenes::MemoryNeed>& needs);
// Refuses a figure whose outputs would take more than options.max_disk:
// each file's most (app/formats.hpp's table) and the parts of its work
// items kept while it runs (`parts_bytes`, the scene's bound).
void require_disk(const Description& d, const OutputOptions& options, double parts_bytes = 0);
// A film frame's pixels at the output scale (0 without a film).
double frame_pixels(const Description& d, const OutputOptions& options);
// Whether figure `d` gets a file drawn on a vector page (PDF, SVG).
bool writes_vector(const Description& d, const OutputOptions& options);
// "1.5 GiB", "12 MiB", "640 KiB", "100 bytes".
std::string format_bytes(double bytes);

// Receives the animation's frames as the model runs and passes each to a
// thread that encodes and writes it (app/frame_pipe.hpp) while the next is
// simulated and drawn: nothing is kept in memory but the frames queued
// (frames_queued) and the one being encoded.
class FrameSink : public scenes::Film {
public:
    static constexpr int frames_queued = 2;

    // `segments`, when given, are the whole film made elsewhere
    // (app/film_segments.hpp): no frame is added, finish() writes them.
    // `encoders`: the film's segments encoded side by side (MemoryEstimate::film_encoders).
    FrameSink(const Description& d, const OutputOptions& options, const base::Folder& folder, int width, int height,
              const std::vector<nlohmann::json>* segments = nullptr, int encoders = 1);
    ~FrameSink() override;
    void add(render::Image frame, int step) override;
    nlohmann::json finish() override;  // completes the MP4; returns the animation's metadata

private:
    void write(render::Image& frame, int step);  // on the pipe's thread, frame by frame in order

    const Description& description_;
    const OutputOptions& options_;
    base::Folder folder_;
    std::unique_ptr<render::VideoWriter> video_;
    std::unique_ptr<SegmentEncoders> encoders_;  // the film's segments side by side, into video_
    std::unique_ptr<base::AtomicDir> frames_;    // the PNG sequence, in place at finish()
    nlohmann::json steps_ = nlohmann::json::array();
    int width_, height_;
    const std::vector<nlohmann::json>* segments_;
    std::unique_ptr<FramePipe> pipe_;  // last: its thread stops before the writers it uses go
};

// A figure's files in the output folder: what a scene writes through.
class FigureFiles : public scenes::Output {
public:
    // `film_segments`: the film's segments, made by other processes; the
    // scene then draws no frame (film_frames() is empty).
    FigureFiles(const Description& d, const OutputOptions& options, base::Folder folder, scenes::Progress& progress,
                MemoryEstimate memory, const std::vector<nlohmann::json>* film_segments = nullptr)
        : description_(d),
          options_(options),
          folder_(std::move(folder)),
          progress_(progress),
          memory_(std::move(memory)),
          film_segments_(film_segments) {}
    std::unique_ptr<scenes::Film> film(int width, int height) override;
    void figure(const scenes::FigureDrawing& drawing, nlohmann::json metadata) override;
    scenes::Progress& progress() override { return progress_; }
    std::vector<nlohmann::json> results(const scenes::WorkItems& items) override {
        return run_work(description_, items, folder_, options_.work, progress_);
    }
    scenes::FrameRange film_frames() const override {
        return film_segments_ ? scenes::FrameRange{0, 0} : scenes::FrameRange{};
    }

private:
    const Description& description_;
    const OutputOptions& options_;
    base::Folder folder_;
    scenes::Progress& progress_;
    MemoryEstimate memory_;
    const std::vector<nlohmann::json>* film_segments_;
};

// Writes <id>.png and <id>.json. `metadata` holds what the scene knows
// (params, panels with statistics and hashes, animation); the common fields
// (id, title, source, seed, version, renderer, memory estimate) are added here.
void write_figure(const Description& d, const OutputOptions& options, const base::Folder& folder,
                  const MemoryEstimate& memory, const render::Image& image, nlohmann::json metadata);

// The names of figure `id`'s files in the output folder (one per format).
std::vector<std::string> output_names(const std::string& id);

}  // namespace app
