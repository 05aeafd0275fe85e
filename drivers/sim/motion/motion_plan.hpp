#pragma once
// The simulated controller's motion without threads or a running clock: the queue of solved
// segments, the speed profile planned over it, the triggers riding on it, StopMove / StartMove /
// ClearPath, and the trajectory recorded as the robot is advanced to a simulated time.
// MotionSimulator owns the thread, the lock and the clock around it (docs/sim-motion.md).

#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/sim/motion/motion_simulator.hpp"
#include "drivers/sim/motion/path_segment.hpp"
#include "drivers/sim/motion/speed_profile.hpp"
#include "drivers/sim/motion/trajectory_recorder.hpp"
#include "drivers/sim/motion/trigger_schedule.hpp"
#include "drivers/sim/sim_clock.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

namespace fibrecell::drivers::sim {

class MotionPlan {
  public:
    // `clock` only maps simulated time to the steady clock in the samples; the robot starts
    // standing at options.start_joints at simulated time `t_s`.
    MotionPlan(const SimClock& clock, const MotionOptions& options, double t_s);

    // Solves `move` from the end of the queue (or where the robot stands) and appends it;
    // returns its id. Throws MotionError and queues nothing.
    std::uint64_t append(const MotionSegment& move);
    // StopMove: brake at the set acceleration to a standstill on the path (at the next stop
    // point instead when that comes first).
    void stop();
    // StartMove: lift the stop.
    void resume();
    // ClearPath: every unfinished segment loses its triggers; a standing robot drops them all,
    // a moving one stops (as stop()) and drops them once standing.
    void clear();
    // Motors off: standstill where the robot is, the queue dropped.
    void halt();

    // The robot stood idle up to `t_s` [s] (only when !active()).
    void idle_until(double t_s);
    // Moves the robot on to simulated time `t_s` [s]: records the samples up to it, updates
    // current(); returns the callbacks of the triggers due, in path order, for the caller to run
    // outside its lock. The segments it passed finish at settle(), so that whoever waits for
    // them sees their triggers fired.
    std::vector<std::function<void()>> advance_to(double t_s);
    // Finishes what the last advance_to() passed: segments, the standstill. Every command
    // settles first.
    void settle();

    // A motion is planned: the robot moves, turns or is about to start.
    bool active() const { return !profile_.empty(); }
    double time() const { return t_; }  // simulated time of the robot's state [s]
    std::optional<double> next_trigger_s() const { return triggers_.next_due(); }
    bool stopped() const { return stopped_; }
    std::size_t pending() const;  // queued segments not yet finished, ClearPath's excluded
    std::uint64_t last_done() const { return last_done_; }
    // Finished, or dropped by ClearPath / halt().
    bool done(std::uint64_t id) const;
    TrajectorySample current() const;  // the robot at time()
    // CRobT: the robot at time() as a robtarget of `tool` in `wobj`.
    rapid::Robtarget robtarget(const rapid::ToolData& tool, const rapid::WobjData& wobj) const {
        return robtarget_of(pose_now(), tool, wobj, robot_.geometry);
    }
    // Counts the changes status() waiters care about: starts, stops, finished segments.
    std::uint64_t changes() const { return changes_; }
    std::vector<TrajectorySample> take_trajectory() { return recorder_.take(); }
    std::uint64_t samples_dropped() const { return recorder_.dropped(); }

  private:
    double junction_cap(std::size_t i) const;
    double standstill_position() const;
    RobotPose pose_now() const;
    TrajectorySample sample(const RobotPose& pose, double speed_mm_s, double t_s) const;
    TrajectorySample sample_at(double t_s) const;
    TrajectorySample sample_at_end(std::size_t planned) const;
    void replan();
    void record_until(double t_s);
    void finish_segments();
    void standstill();

    const SimClock& clock_;
    MotionOptions options_;
    abb::RobotModel robot_;
    std::deque<PathSegment> queue_;
    RobotPose tail_;  // where the next appended segment starts

    SpeedProfile profile_;            // from t_ over queue_; empty: standing
    std::size_t profile_offset_ = 0;  // segments finished since it was planned
    bool profile_cut_ = false;        // its last segment ends at the stop, not at its end
    TriggerSchedule triggers_;
    std::optional<double> stop_at_mm_;  // path position a stop in force ends at
    bool stopped_ = false;

    double t_ = 0;
    bool unsettled_ = false;  // advanced to t_, not settled yet
    ProfilePoint where_;      // the robot on queue_.front() (as of the last settle)
    TrajectoryRecorder recorder_;
    double motion_start_t_ = 0;       // the record period counts from here
    std::uint64_t records_done_ = 0;  // periodic samples since motion_start_t_

    std::uint64_t next_id_ = 1;
    std::uint64_t last_done_ = 0;
    std::uint64_t changes_ = 0;
};

}  // namespace fibrecell::drivers::sim
