#include "base/background.hpp"

#include <vector>

namespace base {
namespace {

struct Started {
    std::mutex lock;
    std::vector<std::function<void()>> waits;
};

Started& started() {
    static Started* all = new Started;  // never destroyed: waited for before exit
    return *all;
}

}  // namespace

void on_background_started(std::function<void()> wait) {
    Started& s = started();
    std::lock_guard<std::mutex> hold(s.lock);
    s.waits.push_back(std::move(wait));
}

void wait_for_background() {
    std::vector<std::function<void()>> waits;
    {
        Started& s = started();
        std::lock_guard<std::mutex> hold(s.lock);
        waits = s.waits;
    }
    for (const auto& wait : waits) wait();
}

}  // namespace base
