#pragma once
// A progress bar on stderr for long renders, counting units of work
// (simulation steps, frames drawn and encoded). Silent when stderr is not a
// terminal, so logs and CI output stay clean.

#include <atomic>
#include <chrono>
#include <string>

#include "scenes/output.hpp"

namespace app {

class ProgressBar : public scenes::Progress {
public:
    explicit ProgressBar(bool enabled);
    static ProgressBar for_stderr();  // enabled when stderr is a terminal

    void start(const std::string& label, long long total) override;
    void advance(long long units = 1) override;
    void finish() override;  // completes the bar and ends its line

private:
    void draw(bool force);

    bool enabled_;
    std::string label_;
    long long total_ = 0, done_ = 0;
    std::chrono::steady_clock::time_point started_, last_draw_;
};

// Counts the work as it passes it on to `next` (the bar, or the Python
// module's callback), to say where a failed render got to.
class ProgressTally : public scenes::Progress {
public:
    explicit ProgressTally(scenes::Progress& next) : next_(next) {}
    void start(const std::string& label, long long total) override;
    void advance(long long units = 1) override;
    void finish() override;
    // Where the work is, for a message: "tc7-2, 350 of 7001 units of work done".
    std::string position() const;

private:
    scenes::Progress& next_;
    std::string label_;
    long long total_ = 0;
    std::atomic<long long> done_{0};
};

}  // namespace app
