#pragma once
// The recorded TCP trajectory until its owner takes it: time-ordered, one sample per instant (the
// later one recorded for it wins: a segment end over a periodic sample, a stop over both), and
// bounded (past `max_samples` the oldest are dropped and counted) so that a simulator nobody
// drains cannot grow without limit.

#include "drivers/sim/motion/motion_simulator.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

namespace fibrecell::drivers::sim {

class TrajectoryRecorder {
  public:
    explicit TrajectoryRecorder(std::size_t max_samples) : max_samples_(max_samples) {}

    // Appends `s` (not earlier than the last sample), or replaces a sample of the same instant.
    void record(TrajectorySample s) {
        if (s.t_s < last_t_s_) return;
        if (!samples_.empty() && samples_.back().t_s == s.t_s) {
            samples_.back() = std::move(s);
            return;
        }
        last_t_s_ = s.t_s;
        samples_.push_back(std::move(s));
        if (samples_.size() > max_samples_) {
            samples_.pop_front();
            ++dropped_;
        }
    }

    // Every sample since the last take, oldest first.
    std::vector<TrajectorySample> take() {
        std::vector<TrajectorySample> out(std::make_move_iterator(samples_.begin()),
                                          std::make_move_iterator(samples_.end()));
        samples_.clear();
        return out;
    }

    std::uint64_t dropped() const { return dropped_; }

  private:
    std::size_t max_samples_;
    std::deque<TrajectorySample> samples_;
    double last_t_s_ = -std::numeric_limits<double>::infinity();
    std::uint64_t dropped_ = 0;
};

}  // namespace fibrecell::drivers::sim
