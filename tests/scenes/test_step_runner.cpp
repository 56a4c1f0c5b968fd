// The step runner: which steps become frames and panels, where a run stops,
// and what reaches the outputs, with a counter for a model and an Output
// that records what it is given.
#include <catch2/catch.hpp>
#include <memory>
#include <vector>

#include "description/description.hpp"
#include "render/gl/canvas.hpp"
#include "scenes/helpers/step_runner.hpp"

namespace {

struct RecordingFilm : scenes::Film {
    std::vector<int>* steps;
    explicit RecordingFilm(std::vector<int>* s) : steps(s) {}
    void add(const scenes::FrameDrawing&, int step) override { steps->push_back(step); }
    nlohmann::json finish() override { return {{"frames", steps->size()}}; }
};

struct RecordingOutput : scenes::Output {
    std::vector<int> frames;
    nlohmann::json metadata;
    scenes::Progress quiet;
    std::unique_ptr<scenes::Film> film(int, int) override { return std::make_unique<RecordingFilm>(&frames); }
    void figure(const scenes::FigureDrawing&, nlohmann::json meta) override { metadata = std::move(meta); }
    scenes::Progress& progress() override { return quiet; }
    std::vector<nlohmann::json> results(const scenes::WorkItems& items) override {
        std::vector<nlohmann::json> r;
        for (int i = 0; i < items.item_count(); ++i) r.push_back(items.run_item(i));
        return r;
    }
};

// A description with panels at `panels` and an animation over [first, last] every `stride`.
description::Description film_of(std::vector<int> panels, int first, int last, int stride) {
    description::Description d;
    d.id = "runner";
    d.panels = std::move(panels);
    d.animation = description::Animation{first, last, stride, 30, 8, 8, "step {step}"};
    return d;
}

// The frame every frame hook draws, read back by the runner.
scenes::FrameDrawing frame_canvas() {
    return {[](render::Surface& surface) { surface.background({1, 1, 1, 1}); }, 1};
}

// A model that counts its steps and stops changing at `fixed_point`.
struct Counter {
    int steps = 0, fixed_point;
    bool step() { return ++steps < fixed_point; }
};

}  // namespace

TEST_CASE("the runner stops at the last step an output needs and films the animation's steps", "[step-runner]") {
    const auto d = film_of({2, 5}, 0, 9, 3);
    RecordingOutput out;
    const scenes::SceneOptions options{1.0, true};
    scenes::StepRunner run(d, options, out);
    REQUIRE(run.last_step() == 9);
    Counter model{0, 1000};
    std::vector<int> panels;
    const int reached = run.run({.check = {},
                                 .panel = [&](int step) { panels.push_back(step); },
                                 .frame = [&](int) -> scenes::FrameDrawing { return frame_canvas(); },
                                 .advance = [&] { return model.step(); }});
    CHECK(reached == 9);
    CHECK(model.steps == 9);  // never past the last step any output needs
    CHECK(panels == std::vector<int>{2, 5});
    CHECK(out.frames == std::vector<int>{0, 3, 6, 9});
    run.write_figure({8, 8, false, [](render::Surface&) {}}, {});
    CHECK(out.metadata["model_steps"] == 9);
    CHECK(out.metadata["animation"]["frames"] == 4);
}

TEST_CASE("a model that stops early ends the film on its final state", "[step-runner]") {
    const auto d = film_of({}, 0, 20, 3);
    const scenes::SceneOptions options{1.0, true};
    SECTION("a fixed point: the step that changed nothing is the last") {
        RecordingOutput out;
        scenes::StepRunner run(d, options, out);
        Counter model{0, 7};
        const int reached = run.run({.check = {},
                                     .panel = {},
                                     .frame = [&](int) -> scenes::FrameDrawing { return frame_canvas(); },
                                     .advance = [&] { return model.step(); }});
        CHECK(reached == 7);
        CHECK(model.steps == 7);
        CHECK(out.frames == std::vector<int>{0, 3, 6, 7});
    }
    SECTION("a stop rule: the model takes no step once it holds") {
        RecordingOutput out;
        scenes::StepRunner run(d, options, out);
        Counter model{0, 1000};
        const int reached = run.run({.check = {},
                                     .panel = {},
                                     .frame = [&](int) -> scenes::FrameDrawing { return frame_canvas(); },
                                     .advance = [&] { return model.step(); },
                                     .stopped = [&] { return model.steps == 5; }});
        CHECK(reached == 5);
        CHECK(model.steps == 5);
        CHECK(out.frames == std::vector<int>{0, 3, 5});
    }
}

TEST_CASE("run_to_stop goes past the last step to the model's stop, filming only the runs given a frame hook",
          "[step-runner]") {
    const auto d = film_of({}, 0, 4, 2);
    RecordingOutput out;
    const scenes::SceneOptions options{1.0, true};
    scenes::StepRunner run(d, options, out);
    Counter first{0, 12}, second{0, 3};
    CHECK(run.run_to_stop({.check = {}, .panel = {}, .frame = {}, .advance = [&] { return first.step(); }}) == 12);
    CHECK(out.frames.empty());
    CHECK(run.run_to_stop({.check = {},
                           .panel = {},
                           .frame = [&](int) -> scenes::FrameDrawing { return frame_canvas(); },
                           .advance = [&] { return second.step(); }}) == 3);
    CHECK(out.frames == std::vector<int>{0, 2, 3});
    run.write_figure({8, 8, false, [](render::Surface&) {}}, {});
    CHECK(out.metadata["model_steps"] == 15);
}

TEST_CASE("without a film the runner asks for no frame and runs only to the last panel", "[step-runner]") {
    const auto d = film_of({4}, 0, 50, 1);
    RecordingOutput out;
    const scenes::SceneOptions options{1.0, false};
    scenes::StepRunner run(d, options, out);
    Counter model{0, 1000};
    int frames_drawn = 0;
    CHECK(run.run({.check = {},
                   .panel = {},
                   .frame = [&](int) -> scenes::FrameDrawing { return ++frames_drawn, frame_canvas(); },
                   .advance = [&] { return model.step(); }}) == 4);
    CHECK(frames_drawn == 0);
    CHECK(out.frames.empty());
}

TEST_CASE("a kernel's leaps land on every step an output needs and count every step taken", "[step-runner]") {
    const bool film = GENERATE(true, false);
    const auto d = film_of({7, 30}, 4, 20, 5);  // frames at 4, 9, 14, 19; panels at 7 and 30
    RecordingOutput out;
    const scenes::SceneOptions options{1.0, film};
    scenes::StepRunner run(d, options, out);
    std::vector<int> leaps, checked, panels, drawn_at;
    int steps = 0;
    const int reached =
        run.run({.check = [&](int step) { checked.push_back(step); },
                 .panel = [&](int step) { panels.push_back(steps - step); },
                 .frame = [&](int step) -> scenes::FrameDrawing { return drawn_at.push_back(steps - step), frame_canvas(); },
                 .advance = {},
                 .leap = [&](int n) { leaps.push_back(n), steps += n; }});
    CHECK(reached == 30);
    CHECK(steps == 30);
    CHECK(panels == std::vector<int>{0, 0});  // each drawn with the model at its step
    CHECK(drawn_at == std::vector<int>(film ? 4 : 0, 0));
    if (film) {
        CHECK(leaps == std::vector<int>{4, 3, 2, 5, 5, 11});  // to 4, 7, 9, 14, 19, 30
        CHECK(checked == std::vector<int>{0, 4, 7, 9, 14, 19, 30});
        CHECK(out.frames == std::vector<int>{4, 9, 14, 19});
    } else {
        CHECK(leaps == std::vector<int>{7, 23});
        CHECK(checked == std::vector<int>{0, 7, 30});
    }
    run.write_figure({8, 8, false, [](render::Surface&) {}}, {});
    CHECK(out.metadata["model_steps"] == 30);
}
