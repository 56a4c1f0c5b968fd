#pragma once
// What a figure writes into the output folder, all through temporary names:
//   <id>.png            the panels, with id, seed and parameters in tEXt chunks
//   <id>.mp4            the animation, streamed frame by frame
//   <id>-frames/NNNNN.png  the same frames as a PNG sequence (--frames)
//   <id>.json           metadata of all of them: parameters, seed, per-panel
//                       step, statistics and state hash, frame list

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "figures/description.hpp"
#include "render/image.hpp"
#include "render/video.hpp"

namespace figures {

struct OutputOptions {
    std::filesystem::path dir = "out";  // created if missing
    double scale = 1.0;                 // multiplies every size in pixels
    bool video = true;                  // write <id>.mp4
    bool frames = false;                // write <id>-frames/*.png
    render::VideoOptions video_options;

    bool animates() const { return video || frames; }
};

// Pixel size at the given scale, rounded up to even (what H.264 in yuv420p needs).
int scaled_even(int pixels, double scale);
// The figure's size in pixels at the output scale.
int figure_width(const Description& d, const OutputOptions& options);
int figure_height(const Description& d, const OutputOptions& options);

// Receives the animation's frames as the model runs and passes each on at
// once: nothing is kept in memory but the frame being encoded.
class FrameSink {
public:
    FrameSink(const Description& d, const OutputOptions& options, int width, int height);
    ~FrameSink();
    void add(const render::Image& frame, int step);
    nlohmann::json finish();  // completes the MP4; returns the animation's metadata

private:
    const Description& description_;
    const OutputOptions& options_;
    std::unique_ptr<render::VideoWriter> video_;
    std::filesystem::path frames_dir_;
    nlohmann::json steps_ = nlohmann::json::array();
    int width_, height_;
};

// Writes <id>.png and <id>.json. `metadata` holds what the scene knows
// (params, panels with statistics and hashes, animation); the common fields
// (id, title, source, seed, version, renderer) are added here.
void write_figure(const Description& d, const OutputOptions& options, const render::Image& image,
                  nlohmann::json metadata);

}  // namespace figures
