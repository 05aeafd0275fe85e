#pragma once
// Reading a recorded trajectory (MotionSimulator::take_trajectory) back: where the robot was at
// an instant of the steady clock, e.g. when the mock extruder board executed a command.

#include "drivers/sim/motion/motion_simulator.hpp"
#include "drivers/sim/sim_clock.hpp"

#include <optional>
#include <span>

namespace fibrecell::drivers::sim {

// The robot at steady-clock instant `wall`, from `trajectory` (samples oldest first): linear
// between the two samples around it (t_s, positions [mm], path_mm, speed, joints [rad]; segment
// and source of the earlier one), the sample itself on an exact hit. Nothing when `wall` lies
// before the first or after the last sample.
std::optional<TrajectorySample> sample_at(std::span<const TrajectorySample> trajectory,
                                          SimClock::WallClock::time_point wall);

}  // namespace fibrecell::drivers::sim
