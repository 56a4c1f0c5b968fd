#include "app/render/frame_pipe.hpp"

#include <stdexcept>
#include <utility>

namespace app {

FramePipe::FramePipe(Consume consume, int depth)
    : consume_(std::move(consume)), depth_(depth < 1 ? throw std::invalid_argument("FramePipe depth < 1") : depth) {
    thread_ = std::thread([this] { run(); });
}

FramePipe::~FramePipe() {
    {
        std::lock_guard hold(lock_);
        queue_.clear();
    }
    stop();
}

void FramePipe::rethrow_failure() {
    if (failure_) std::rethrow_exception(failure_);  // sticky: every later call fails too
}

void FramePipe::push(render::Image frame, int step) {
    std::unique_lock hold(lock_);
    changed_.wait(hold, [&] { return queue_.size() < depth_ || failure_; });
    rethrow_failure();
    queue_.push_back({std::move(frame), step});
    changed_.notify_all();
}

void FramePipe::finish() {
    {
        std::unique_lock hold(lock_);
        changed_.wait(hold, [&] { return (queue_.empty() && !busy_) || failure_; });
    }
    stop();
    rethrow_failure();
}

void FramePipe::stop() {
    {
        std::lock_guard hold(lock_);
        closing_ = true;
        changed_.notify_all();
    }
    if (thread_.joinable()) thread_.join();
}

void FramePipe::run() {
    for (;;) {
        Item item;
        {
            std::unique_lock hold(lock_);
            changed_.wait(hold, [&] { return !queue_.empty() || closing_; });
            if (queue_.empty()) return;  // closing, nothing left
            item = std::move(queue_.front());
            queue_.pop_front();
            busy_ = true;
            changed_.notify_all();  // room in the queue: a producer waiting in push() goes on now
        }
        try {
            consume_(item.frame, item.step);  // the consumer may move the frame away
        } catch (...) {
            std::lock_guard hold(lock_);
            failure_ = std::current_exception();
            queue_.clear();
        }
        std::lock_guard hold(lock_);
        busy_ = false;
        changed_.notify_all();
        if (failure_) return;
    }
}

}  // namespace app
