#pragma once
// A film's frames handed from the thread that simulates and draws them to one
// thread that encodes and writes them, through a queue of a few frames: the
// model, llvmpipe and x264 work at the same time, and no more than `depth`
// frames wait in memory. Frames are consumed one at a time in the order they
// were pushed, so what is written does not depend on timing.

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "render/image.hpp"

namespace app {

class FramePipe {
public:
    // The frame is the consumer's to keep (move from) or drop.
    using Consume = std::function<void(render::Image& frame, int step)>;
    // Starts the consuming thread. depth >= 1.
    FramePipe(Consume consume, int depth);
    // Without finish(): stops the consumer after the frame it is on and drops the rest.
    ~FramePipe();
    FramePipe(const FramePipe&) = delete;
    FramePipe& operator=(const FramePipe&) = delete;

    // Waits while `depth` frames are queued; rethrows what the consumer threw.
    void push(render::Image frame, int step);
    // Waits until every frame is consumed and the thread has ended; rethrows
    // what the consumer threw.
    void finish();

private:
    struct Item {
        render::Image frame;
        int step;
    };
    void run();
    void stop();  // ends the thread and joins it
    void rethrow_failure();

    Consume consume_;
    const std::size_t depth_;
    std::mutex lock_;
    std::condition_variable changed_;
    std::deque<Item> queue_;
    bool closing_ = false, busy_ = false;
    std::exception_ptr failure_;
    std::thread thread_;  // last: started once everything above exists
};

}  // namespace app
