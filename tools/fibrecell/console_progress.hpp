#pragma once
// Planner progress on the terminal: one line per stage with its time; on a terminal the current
// stage's percentage is redrawn in place.

#include "planner/progress.hpp"

#include <chrono>
#include <string>

namespace fibrecell::tools {

class ConsoleProgress {
  public:
    ConsoleProgress();
    ~ConsoleProgress();
    planner::ProgressSink sink();
    void update(std::string_view stage, double fraction);
    void finish();  // closes the current stage line

  private:
    bool tty_;
    std::string stage_;
    std::chrono::steady_clock::time_point stage_start_;
    int last_percent_ = -1;
};

}  // namespace fibrecell::tools
