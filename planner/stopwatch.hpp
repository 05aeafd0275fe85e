#pragma once
// Wall-clock timing of planner steps, for the report's timings_s.

#include <chrono>

namespace fibrecell::planner {

class Stopwatch {
  public:
    // Seconds since construction or the last lap, and restarts.
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(now - last_).count();
        last_ = now;
        return s;
    }
    double elapsed() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

  private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point last_ = start_;
};

}  // namespace fibrecell::planner
