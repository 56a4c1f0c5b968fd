#pragma once
// What a scene draws into, as the command (app/) provides it: the figure,
// its film, the progress of the run. The scene does not know where or how
// the files are written.

#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ready/state.hpp"
#include "render/image.hpp"
#include "render/surface.hpp"
#include "scenes/work_items.hpp"

namespace scenes {

// Counts units of work (model steps, frames, runs) for a progress display.
// The default shows nothing.
class Progress {
public:
    virtual ~Progress() = default;
    virtual void start(const std::string& /*label*/, long long /*total*/) {}
    virtual void advance(long long /*units*/ = 1) {}
    virtual void finish() {}
};

// A film's frame as the scene describes it: `draw` draws it on a surface of
// the film's frame size, and the canvas it needs (made once, from the first
// frame's samples and depth buffer). The command draws it (on the GL
// canvas it owns, app/render/frame_canvas.hpp) and reads it back.
struct FrameDrawing {
    std::function<void(render::Surface&)> draw;
    int samples = 4;     // the canvas's multisampling
    bool depth = false;  // a depth buffer, for 3-D scenes
};

// The animation: its frames handed over as drawings, in step order.
class Film {
public:
    virtual ~Film() = default;
    // Draws `frame`, the film's frame at `step`, at once (what it captures
    // need not outlive the call); it reaches the files a few frames later.
    virtual void add(const FrameDrawing& frame, int step) = 0;
    // Every frame added so far passed on to the files (the end of a model's run).
    virtual void flush() {}
    virtual nlohmann::json finish() = 0;  // completes it; returns the animation's metadata
};

// Which of the animation's frames a run draws, by frame index (the n-th
// frame of the film): [first, end). A whole render draws them all; a run
// that makes one segment of a film on another process draws that segment's;
// the run that writes a film whose segments were made elsewhere draws none.
struct FrameRange {
    int first = 0, end = std::numeric_limits<int>::max();
    bool holds(int index) const { return index >= first && index < end; }
    bool all() const { return first == 0 && end == std::numeric_limits<int>::max(); }
};

// The figure as the scene describes it: `draw` draws it on a surface of
// width x height pixels, whichever backend that is (render/surface.hpp: the
// GL canvas for the PNG, a vector page for PDF and SVG). The command calls
// it once per format, so it must draw the same every time and change
// nothing else; what the figure's metadata needs is worked out before.
struct FigureDrawing {
    int width = 0, height = 0;
    bool depth = false;  // it draws 3-D tubes (a GL canvas with a depth buffer)
    std::function<void(render::Surface&)> draw;
    // A formula model's last step, for Ready's VTI file (--format vti,
    // written by the command: ready/writers/); null for the scenes that
    // write none.
    std::function<ready::ReadyState()> ready_state = {};
};

// Where a scene's outputs go.
class Output {
public:
    virtual ~Output() = default;
    // The film of width x height frames; null when no animation is written.
    virtual std::unique_ptr<Film> film(int width, int height) = 0;
    // The figure and the scene's metadata (params, panels, statistics, hashes).
    virtual void figure(const FigureDrawing& drawing, nlohmann::json metadata) = 0;
    virtual Progress& progress() = 0;
    // Every work item's result, in item order: run here on threads, over
    // MPI ranks, or read from the parts of earlier runs and shards
    // (app/work/schedule.hpp decides). Advances progress() by one per item.
    virtual std::vector<nlohmann::json> results(const WorkItems& items) = 0;
    // The film's frames this run draws (scenes/helpers/step_runner.cpp keeps to it).
    virtual FrameRange film_frames() const { return {}; }
    // False for a run that only makes film frames: its figure is not drawn.
    virtual bool wants_figure() const { return true; }
};

}  // namespace scenes
