// The film's frame pipe: frames reach the consuming thread in order, no more
// than its depth wait, and what the consumer throws reaches the producer.
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "app/render/frame_pipe.hpp"

namespace {

render::Image frame_marked(int value) {
    render::Image image(2, 1);
    image.rgba[0] = static_cast<std::uint8_t>(value);
    return image;
}

}  // namespace

TEST_CASE("the frame pipe hands every frame over in the order pushed, with at most its depth waiting") {
    const int depth = GENERATE(1, 2, 5);
    std::vector<int> steps, marks;
    std::atomic<int> pushed{0};
    int most_waiting = 0;
    app::FramePipe pipe(
        [&](const render::Image& frame, int step) {
            if (step == 0) {
                // A slow encoder on the first frame: the producer runs ahead
                // until the queue is full (waited for, up to 10 s on a busy machine).
                for (int i = 0; i < 10000 && pushed.load() < depth + 1; ++i)
                    std::this_thread::sleep_for(std::chrono::milliseconds(1));
                std::this_thread::sleep_for(std::chrono::milliseconds(5));  // a push past the queue would land now
            }
            // The frames whose push returned but that are not yet taken: those queued.
            most_waiting = std::max(most_waiting, pushed.load() - static_cast<int>(steps.size()) - 1);
            steps.push_back(step);
            marks.push_back(frame.rgba[0]);
        },
        depth);
    for (int i = 0; i < 40; ++i) {
        pipe.push(frame_marked(i), 10 * i);
        ++pushed;
    }
    pipe.finish();
    REQUIRE(steps.size() == 40);
    for (int i = 0; i < 40; ++i) {
        CHECK(steps[i] == 10 * i);
        CHECK(marks[i] == i);
    }
    CHECK(most_waiting == depth);  // the producer ran ahead of the slow consumer by the queue, no further
}

TEST_CASE("what the frame pipe's consumer throws reaches the producer, and later frames are dropped") {
    std::vector<int> steps;
    app::FramePipe pipe(
        [&](const render::Image&, int step) {
            if (step == 3) throw std::runtime_error("cannot write out/x.mp4: No space left on device");
            steps.push_back(step);
        },
        2);
    bool thrown = false;
    try {
        for (int i = 0; i < 100; ++i) pipe.push(frame_marked(i), i);
        pipe.finish();
    } catch (const std::runtime_error& e) {
        thrown = true;
        CHECK(std::string(e.what()) == "cannot write out/x.mp4: No space left on device");
    }
    CHECK(thrown);
    CHECK(steps == std::vector<int>{0, 1, 2});
    CHECK_THROWS_WITH(pipe.finish(), "cannot write out/x.mp4: No space left on device");  // and again
}

TEST_CASE("a frame pipe dropped without finish stops its thread") {
    std::atomic<int> consumed{0};
    {
        app::FramePipe pipe(
            [&](const render::Image&, int) {
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
                ++consumed;
            },
            3);
        for (int i = 0; i < 4; ++i) pipe.push(frame_marked(i), i);
    }  // the destructor drops what waits and joins
    CHECK(consumed.load() <= 4);
    CHECK(consumed.load() >= 1);
}
