#pragma once
// A value made once per process on a thread of its own: start() begins
// making it (calling it again is harmless), get() starts it if need be and
// waits for it. What opens a library (GL, FFmpeg's module) while the
// program reads its inputs and runs the first model. Keep one in a
// function-local static.
//
// A process must not exit while such a thread is still inside dlopen: the
// library's static objects, constructed on that thread, would be destroyed
// by exit() on the main thread at the same time (LLVM's pass registry was
// freed twice when a refused plant ended the program 50 ms after it
// started). main() calls wait_for_background() before it returns.

#include <functional>
#include <future>
#include <mutex>

namespace base {

// Waits for every Background value started in this process.
void wait_for_background();
// What start() registers for wait_for_background().
void on_background_started(std::function<void()> wait);

template <typename T>
class Background {
public:
    explicit Background(T (*make)()) : make_(make) {}

    void start() {
        std::call_once(started_, [this] {
            value_ = std::async(std::launch::async, make_).share();
            on_background_started([future = value_] { future.wait(); });
        });
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

}  // namespace base
