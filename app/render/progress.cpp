#include "app/render/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "app/render/terminal_text.hpp"

namespace app {

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled) {}

ProgressBar ProgressBar::for_stderr() {
    return ProgressBar(::isatty(STDERR_FILENO) == 1);
}

void ProgressBar::start(const std::string& label, long long total) {
    label_ = label;
    total_ = total > 0 ? total : 1;
    done_ = 0;
    started_ = last_draw_ = std::chrono::steady_clock::now();
    draw(true);
}

void ProgressBar::advance(long long units) {
    done_ += units;
    draw(false);
}

void ProgressBar::finish() {
    if (!enabled_) return;
    done_ = total_;
    draw(true);
    std::fputc('\n', stderr);
}

void ProgressTally::start(const std::string& label, long long total) {
    label_ = label;
    total_ = total > 0 ? total : 1;
    done_ = 0;
    next_.start(label, total);
}

void ProgressTally::advance(long long units) {
    done_ += units;
    next_.advance(units);
}

void ProgressTally::finish() {
    next_.finish();
}

std::string ProgressTally::position() const {
    if (label_.empty()) return "before its run started";
    return label_ + ", " + std::to_string(done_.load()) + " of " + std::to_string(total_) + " units of work done";
}

void ProgressBar::draw(bool force) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    // Ten redraws a second are enough for the eye and cost nothing.
    if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    // "label [####      ]  40%    1.2s" in one column less than the
    // terminal has, so that it never wraps: the bar up to 30 wide, the
    // label up to 12 columns, both shorter on a narrow terminal.
    const int columns = terminal_columns(STDERR_FILENO) - 1;
    constexpr int numbers = 16;  // "] 100% 9999.9s" and the " [" before the bar
    const int label_columns = std::clamp(columns - numbers - 10, 0, 12);
    const int width = std::clamp(columns - numbers - (label_columns ? label_columns + 1 : 0), 1, 30);
    const double fraction = done_ >= total_ ? 1.0 : double(done_) / double(total_);
    const int filled = static_cast<int>(fraction * width);
    const double seconds = std::chrono::duration<double>(now - started_).count();
    const std::string label = label_columns ? pad_columns(fit_columns(label_, label_columns), label_columns) + " " : "";
    std::fprintf(stderr, "\r%s[%.*s%*s] %3d%% %6.1fs", label.c_str(), filled, "##############################",
                 width - filled, "", static_cast<int>(fraction * 100), seconds);
    std::fflush(stderr);
}

}  // namespace app
