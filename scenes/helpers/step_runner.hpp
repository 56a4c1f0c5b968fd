#pragma once
// The one run of a stepping model that feeds every output of a figure: it
// knows which steps are panels, which are animation frames, and the last
// step any output needs, so the model never runs past it. Frames go straight
// to the MP4 / PNG sequence as they are drawn.

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>

#include "render/image.hpp"
#include "render/surface.hpp"
#include "scenes/helpers/field_panels.hpp"
#include "scenes/scene.hpp"

namespace scenes {

// What a scene does at each step of the run.
struct StepHooks {
    std::function<void(int step)> check;           // at every step: throws if the model went unstable
    std::function<void(int step)> panel;           // keep what a panel at this step shows
    // The animation's frame at this step (none: not filmed).
    std::function<FrameDrawing(int step)> frame;
    std::function<bool()> advance;                 // one model step; false when the model has stopped (a fixed point)
    std::function<bool()> stopped = {};            // optional: the model has reached its stop and takes no more steps
    // Optional, for a model stepped by a fast kernel: `steps` steps at once
    // (instead of as many advance() calls), to the next step an output
    // needs. It must itself make sure every step it took was sound (and
    // throw naming the first that was not), since check() then runs only at
    // the steps the runner stops at.
    std::function<void(int steps)> leap = {};
    // Optional: more steps a leap stops at, for check() to see (a 1-D
    // model's space-time diagram keeps a row every so many steps).
    std::function<bool(int step)> stop_at = {};
    // Optional, for a 3-D view: the k-th of n frames that turn the camera
    // round the state the run ended at (animation.turn_frames), after the
    // run's own frames.
    std::function<FrameDrawing(int k, int n)> turn = {};
};

class StepRunner {
public:
    StepRunner(const Description& d, const SceneOptions& options, Output& out);

    int last_step() const { return last_; }
    // Whether this run draws film frames (the model then shares the cores with them).
    bool filming() const { return film_ != nullptr; }
    // The film's frame size in pixels.
    int frame_width() const { return frame_width_; }
    int frame_height() const { return frame_height_; }
    // A frame of field panels, with the samples its page needs
    // (field_page_samples; the first frame's make the canvas, the layout stays).
    FrameDrawing field_frame(std::vector<FieldPanel> panels) const;

    // Runs from step 0 to last_step() or until the model stops (advance()
    // or stopped() says so); returns the last step reached.
    int run(const StepHooks& hooks);
    // The same to the model's own stop, whatever last_step() is: for models
    // whose panels show where they stop (percolation). Call it once per model
    // of a figure; the film takes the frames of the runs given a frame hook.
    int run_to_stop(const StepHooks& hooks);

    // A run that makes only some of the film's frames (a segment, on
    // another MPI rank): its figure is not drawn; end it with finish_film().
    bool film_only() const { return !out_.wants_figure(); }
    void finish_film();
    // Completes the animation, adds its metadata to `meta`, writes the
    // figure's PNG and JSON and completes the progress bar.
    void write_figure(const FigureDrawing& figure, nlohmann::json meta);
    // The same for a figure that is a row of field panels, drawn at the
    // figure's size; `ready_state`, if given, is the state for --format vti.
    void write_field_figure(const std::vector<FieldPanel>& panels, nlohmann::json meta,
                            std::function<ready::ReadyState()> ready_state = {});

private:
    int run_until(const StepHooks& hooks, int last);
    int run_steps(const StepHooks& hooks, int last);  // run_until's loop
    void final_frame(const StepHooks& hooks, int step);
    bool is_panel(int step) const;
    int next_stop(const StepHooks& hooks, int step, int last) const;  // the next step an output needs, or last
    // A frame of the film at `step`, drawn by this run (film_frames()).
    bool wants_frame(int step) const {
        return film_ && description_.animation->shows(step) && frames_.holds(frame_index(step));
    }
    // The film's frame at `step`: its regular frames are numbered in step
    // order, and a final frame at a stop between two of them comes after
    // the earlier one.
    int frame_index(int step) const;
    void frame(const FrameDrawing& drawing, int step);  // hands a frame to the film
    void drain_frames();                                 // every frame handed over reaches the film's files
    void stepped();                             // counts one model step (progress bar and metadata)

    const Description& description_;
    const SceneOptions& options_;
    Output& out_;
    Progress& progress_;
    int last_ = 0;
    long long model_steps_ = 0;  // steps the model actually took: the metadata's proof that nothing ran past last_
    int frame_width_ = 0, frame_height_ = 0;
    FrameRange frames_;  // of the film's frames, those this run draws
    std::unique_ptr<Film> film_;
};

}  // namespace scenes
