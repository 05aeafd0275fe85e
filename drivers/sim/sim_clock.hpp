#pragma once
// Simulated time for the simulated cell: simulated seconds run `time_scale` times faster than the
// steady clock, from the moment the clock was made. The motion simulator and the RAPID task share
// one clock, so that a WaitUntil \MaxTime, an ITimer and a move all age at the same rate; the
// wall-clock mapping lets tests line up the robot's trajectory with the mock board's log.

#include <chrono>
#include <stdexcept>
#include <thread>

namespace fibrecell::drivers::sim {

class SimClock {
  public:
    using WallClock = std::chrono::steady_clock;

    explicit SimClock(double time_scale = 1.0) : scale_(time_scale), t0_(WallClock::now()) {
        if (!(time_scale > 0)) throw std::invalid_argument("time scale must be positive");
    }

    double time_scale() const { return scale_; }
    // Simulated seconds since the clock was made.
    double now_s() const { return sim_at(WallClock::now()); }
    double sim_at(WallClock::time_point wall) const {
        return std::chrono::duration<double>(wall - t0_).count() * scale_;
    }
    WallClock::time_point wall_at(double sim_s) const {
        return t0_ + std::chrono::duration_cast<WallClock::duration>(
                         std::chrono::duration<double>(sim_s / scale_));
    }
    // Sleeps until simulated time `sim_s` (returns at once when it has passed).
    void sleep_until(double sim_s) const { std::this_thread::sleep_until(wall_at(sim_s)); }

  private:
    double scale_;
    WallClock::time_point t0_;
};

}  // namespace fibrecell::drivers::sim
