#include "scenes/helpers/figure_caption.hpp"
#include "scenes/helpers/step_runner.hpp"

#include <algorithm>
#include <limits>

namespace scenes {

StepRunner::StepRunner(const Description& d, const SceneOptions& options, Output& out)
    : description_(d), options_(options), out_(out), progress_(out.progress()) {
    const bool animate = d.animation && options.film;
    last_ = d.last_step(animate);
    frames_ = out.film_frames();
    // A run that makes only some of the film's frames stops after its last
    // (the frames that turn round the last step need the whole run).
    if (animate && !out.wants_figure() && frames_.end > 0 && frames_.end < d.animation->run_frames())
        last_ = std::min(last_, d.animation->first + (frames_.end - 1) * d.animation->stride);
    if (animate) {
        frame_width_ = scaled_even(d.animation->width, options.scale);
        frame_height_ = scaled_even(d.animation->height, options.scale);
        film_ = out.film(frame_width_, frame_height_);
    }
    progress_.start(d.id, last_ + 1 + (animate ? d.animation->frame_count() : 0));
}

bool StepRunner::is_panel(int step) const {
    return std::binary_search(description_.panels.begin(), description_.panels.end(), step);
}

int StepRunner::run(const StepHooks& hooks) {
    return run_until(hooks, last_);
}

int StepRunner::run_to_stop(const StepHooks& hooks) {
    return run_until(hooks, std::numeric_limits<int>::max());
}

int StepRunner::run_until(const StepHooks& hooks, int last) {
    const int reached = run_steps(hooks, last);
    if (film_ && hooks.turn) {
        // The frames after the run's, numbered after them whatever the run drew.
        const description::Animation& a = *description_.animation;
        for (int k = 0; k < a.turn_frames; ++k)
            if (frames_.holds(a.run_frames() + k)) frame(hooks.turn(k, a.turn_frames), reached);
    }
    drain_frames();  // every frame read back and in the film when the run ends
    return reached;
}

int StepRunner::run_steps(const StepHooks& hooks, int last) {
    for (int step = 0;; ++step) {
        const bool is_panel = this->is_panel(step), is_frame = hooks.frame && wants_frame(step);
        // Every step, not only those drawn: a run that goes bad stops at the
        // step it went bad, before anything is written.
        if (hooks.check) hooks.check(step);
        if (is_panel && hooks.panel) hooks.panel(step);
        if (is_frame) frame(hooks.frame(step), step);
        if (step == last) return step;
        if (hooks.stopped && hooks.stopped()) {
            if (!is_frame) final_frame(hooks, step);
            return step;
        }
        if (hooks.leap) {
            const int next = next_stop(hooks, step, last);
            hooks.leap(next - step);
            model_steps_ += next - step - 1;
            progress_.advance(next - step - 1);
            stepped();
            step = next - 1;
            continue;
        }
        const bool going = hooks.advance();
        stepped();
        if (!going) {
            if (!wants_frame(step + 1)) final_frame(hooks, step + 1);
            return step + 1;
        }
    }
}

int StepRunner::next_stop(const StepHooks& hooks, int step, int last) const {
    // A leap of at most this many steps when no output bounds it (run_to_stop).
    constexpr int longest_leap = 1000;
    int next = step + 1;
    while (next < last && next - step < longest_leap && !is_panel(next) && !(hooks.frame && wants_frame(next)) &&
           !(hooks.stop_at && hooks.stop_at(next)))
        ++next;
    return next;
}

int StepRunner::frame_index(int step) const {
    const description::Animation& a = *description_.animation;
    if (step <= a.first) return 0;
    return (step - a.first - 1) / a.stride + 1;  // the regular frames at first, first + stride, ... before or at it
}

// The state no longer changes: it ends the film as its final frame if the
// animation would have gone on.
void StepRunner::final_frame(const StepHooks& hooks, int step) {
    if (film_ && hooks.frame && step <= description_.animation->last && frames_.holds(frame_index(step)))
        frame(hooks.frame(step), step);
}

void StepRunner::frame(const FrameDrawing& drawing, int step) {
    film_->add(drawing, step);
    progress_.advance();
}

void StepRunner::drain_frames() {
    if (film_) film_->flush();
}

FrameDrawing StepRunner::field_frame(std::vector<FieldPanel> panels) const {
    return field_page(std::move(panels), frame_width_, frame_height_, options_.scale, LayerPasses::paired);
}

void StepRunner::stepped() {
    ++model_steps_;
    progress_.advance();
}

void StepRunner::write_figure(const FigureDrawing& figure, nlohmann::json meta) {
    drain_frames();
    if (film_) meta["animation"] = film_->finish();
    meta["model_steps"] = model_steps_;
    out_.figure(figure, std::move(meta));
    progress_.finish();
}

void StepRunner::finish_film() {
    drain_frames();
    if (film_) film_->finish();
    progress_.finish();
}

void StepRunner::write_field_figure(const std::vector<FieldPanel>& panels, nlohmann::json meta,
                                    std::function<ready::ReadyState()> ready_state) {
    if (film_only()) return finish_film();
    FigureDrawing figure = field_figure(panels, description_, options_);
    figure.ready_state = std::move(ready_state);
    write_figure(figure, std::move(meta));
}

}  // namespace scenes
