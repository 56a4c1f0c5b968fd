#pragma once
// A progress bar on stderr for long renders, counting units of work
// (simulation steps, frames drawn and encoded). Silent when stderr is not a
// terminal, so logs and CI output stay clean.

#include <chrono>
#include <string>

namespace figures {

struct DescribeStop {};  // thrown where a describe-only run has read its settings

class Progress {
public:
    explicit Progress(bool enabled);
    static Progress for_stderr();  // enabled when stderr is a terminal

    // Throws DescribeStop when describe_only: `figgen describe` runs a scene
    // only as far as it reads its settings.
    void start(const std::string& label, long long total);
    bool describe_only = false;
    void advance(long long units = 1);
    void finish();  // completes the bar and ends its line

private:
    void draw(bool force);

    bool enabled_;
    std::string label_;
    long long total_ = 0, done_ = 0;
    std::chrono::steady_clock::time_point started_, last_draw_;
};

}  // namespace figures
