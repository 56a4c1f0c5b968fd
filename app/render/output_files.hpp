#pragma once
// What a figure writes into the output folder, all through temporary names:
//   <id>.png            the panels, with id, seed and parameters in tEXt chunks
//   <id>.mp4            the animation, streamed frame by frame
//   <id>.webp           its short looping preview (animated WebP), with the MP4
//   <id>.webm           the film as VP9 in WebM, for the web (--format webm)
//   <id>.pdf, <id>.svg  the figure as vector graphics (--format pdf, svg)
//   <id>.vti            a formula model's last step as Ready's file (--format vti)
//   <id>.vtu            a mesh model's last step as Ready's file (--format vtu)
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

#include "app/render/estimates.hpp"
#include "app/render/frame_canvas.hpp"
#include "app/render/frame_pipe.hpp"
#include "app/render/output_options.hpp"
#include "app/render/segment_encoders.hpp"
#include "app/work/schedule.hpp"
#include "base/atomic_file.hpp"
#include "description/description.hpp"
#include "media/video.hpp"
#include "render/image.hpp"
#include "scenes/output.hpp"
#include "scenes/scene.hpp"

namespace app {

// Receives the animation's frames as the model runs, draws each on the
// film's canvas (app/render/frame_canvas.hpp) and passes it to a thread
// that encodes and writes it (app/render/frame_pipe.hpp) while the next is
// simulated and drawn: nothing is kept in memory but the frames queued
// (frames_queued) and the one being encoded.
class FrameSink : public scenes::Film {
public:
    static constexpr int frames_queued = 2;

    // `segments`, when given, are the whole film made elsewhere
    // (app/render/film_segments.hpp): no frame is added, finish() writes them.
    // `encoders`: the film's segments encoded side by side (MemoryEstimate::film_encoders).
    FrameSink(const Description& d, const OutputOptions& options, const base::Folder& folder, int width, int height,
              const std::vector<nlohmann::json>* segments = nullptr, int encoders = 1);
    ~FrameSink() override;
    void add(const scenes::FrameDrawing& frame, int step) override;
    void flush() override;
    nlohmann::json finish() override;  // completes the MP4; returns the animation's metadata

private:
    void write(render::Image& frame, int step);  // on the pipe's thread, frame by frame in order

    const Description& description_;
    const OutputOptions& options_;
    base::Folder folder_;
    std::unique_ptr<media::VideoWriter> video_;
    std::unique_ptr<SegmentEncoders> encoders_;  // the film's segments side by side, into video_
    std::unique_ptr<base::AtomicDir> frames_;    // the PNG sequence, in place at finish()
    nlohmann::json steps_ = nlohmann::json::array();
    int width_, height_;
    const std::vector<nlohmann::json>* segments_;
    std::unique_ptr<FramePipe> pipe_;  // its thread stops before the writers it uses go
    FrameCanvas canvas_;               // last: it hands its frames to the pipe
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
