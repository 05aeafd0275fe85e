#include "tools/fibrecell/console_progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace fibrecell::tools {

ConsoleProgress::ConsoleProgress() : tty_(isatty(STDERR_FILENO) == 1) {}

ConsoleProgress::~ConsoleProgress() {
    finish();
}

planner::ProgressSink ConsoleProgress::sink() {
    return [this](std::string_view stage, double fraction) { update(stage, fraction); };
}

void ConsoleProgress::update(std::string_view stage, double fraction) {
    if (stage != stage_) {
        finish();
        stage_ = stage;
        stage_start_ = std::chrono::steady_clock::now();
        last_percent_ = -1;
    }
    const int percent = static_cast<int>(fraction * 100.0 + 0.5);
    if (tty_ && percent != last_percent_) {
        std::fprintf(stderr, "\r  %-22s %3d%%", stage_.c_str(), percent);
        std::fflush(stderr);
    }
    last_percent_ = percent;
}

void ConsoleProgress::finish() {
    if (stage_.empty()) return;
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
    std::fprintf(stderr, "%s  %-22s done in %.3f s\n", tty_ ? "\r" : "", stage_.c_str(), s);
    stage_.clear();
}

}  // namespace fibrecell::tools
