#pragma once
// When the triggers riding on the planned path fire: at the instant the speed profile brings the
// TCP to a trigger's position, or lag_s before it (TriggEquip). Rebuilt whenever the profile is
// replanned, so a lag is always measured along the plan in force.

#include "drivers/sim/motion/path_segment.hpp"
#include "drivers/sim/motion/speed_profile.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

namespace fibrecell::drivers::sim {

class TriggerSchedule {
  public:
    // Schedules the unfired triggers of the segments `profile` covers (queue[i] is its segment
    // i, the first entered at `position_mm` [mm] at time `t_s`); a trigger past `stop_at_mm`
    // (the path position the robot stops at, if a stop is in force) is not reached.
    void plan(const std::deque<PathSegment>& queue, const SpeedProfile& profile, double t_s,
              double position_mm, std::optional<double> stop_at_mm);
    // Marks the triggers due by time `t_s` [s] fired and returns their callbacks in path order.
    std::vector<std::function<void()>> take_due(double t_s, std::deque<PathSegment>& queue);
    void clear() { due_.clear(); }
    // Fire time [s] of the next trigger, if one is scheduled.
    std::optional<double> next_due() const {
        if (due_.empty()) return std::nullopt;
        return due_.front().fire_t_s;
    }

  private:
    struct Due {
        double fire_t_s = 0;
        double path_mm = 0;  // position of the trigger on the whole path
        std::uint64_t segment = 0;
        std::size_t index = 0;  // in the segment's triggers
    };
    std::deque<Due> due_;  // by fire time
};

}  // namespace fibrecell::drivers::sim
