#pragma once
// A value made once per process on a thread of its own: start() begins
// making it (calling it again is harmless), get() starts it if need be and
// waits for it. What opens a library (GL, FFmpeg's module) while the
// program reads its inputs and runs the first model. Keep one in a
// function-local static: its future waits at exit for work still running.

#include <future>
#include <mutex>

namespace render {

template <typename T>
class Background {
public:
    explicit Background(T (*make)()) : make_(make) {}

    void start() {
        std::call_once(started_, [this] { value_ = std::async(std::launch::async, make_).share(); });
    }

    const T& get() {
        start();
        return value_.get();
    }

private:
    T (*make_)();
    std::once_flag started_;
    std::shared_future<T> value_;
};

}  // namespace render
