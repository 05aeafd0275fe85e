#pragma once
// The simulated robot's motion: the path planner and servo of the simulated IRC5, without RAPID.
// The RAPID task (drivers/sim/rapid_exec) queues one segment per MoveL/MoveJ/TriggL/TriggJ and
// goes on (RAPID runs ahead of the robot); a motion thread moves the TCP along the queued segments
// in simulated time (SimClock) with a trapezoidal speed profile at the programmed speeds, fires the
// segments' triggers at their positions, stops on StopMove and records the TCP trajectory.
//
// Model (docs/sim-motion.md):
//   - the TCP moves in straight lines between targets in the base frame (MoveJ too: a documented
//     simplification), orientation slerped; speed = speeddata.v_tcp, or slower when v_ori limits
//     the reorientation;
//   - fly-by points are passed through (no corner cut) at a junction speed that falls with the
//     corner angle; a stop point (fine) and the last queued segment end at speed 0;
//   - one constant acceleration/deceleration for the TCP;
//   - every target is solved with the IRB 1200 IK on its confdata's cfx branch when it is queued:
//     an unreachable target, a joint limit or a cfx that does not match throws MotionError and
//     queues nothing (a controller error, as on a real IRC5).
//
// Thread-safety: every public method may be called from any thread. Trigger callbacks run on the
// motion thread and must not block; they may call the simulator (current() then shows where the
// trigger fired). A segment is reported done only after the callbacks of the tick that finished
// it have run; a callback that throws halts the robot with status().error set.

#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "drivers/abb/kinematics/joint_vector.hpp"
#include "drivers/abb/rapid/robot_data.hpp"
#include "drivers/sim/sim_clock.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

namespace rapid = abb::rapid;  // the RAPID data types the segments carry

// A controller error raised by motion (unreachable target, joint limit, wrong cfx, motors off).
class MotionError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// One trigger riding on a segment (TriggIO / TriggEquip with a distance; \Time is not supported).
struct MotionTrigger {
    double distance_mm = 0;   // before the segment's end point, or after its start with from_start
    bool from_start = false;  // \Start
    double lag_s = 0;         // TriggEquip EquipLag: fire this long before the robot gets there
    std::function<void()> fire;  // called once on the motion thread
};

struct MotionSegment {
    bool joint = false;       // MoveJ/TriggJ (moved as a straight TCP line, see above)
    rapid::Robtarget target;  // TCP in the work object
    rapid::ToolData tool;
    rapid::WobjData wobj;
    rapid::SpeedData speed;
    rapid::ZoneData zone;  // finep: stop point
    std::vector<MotionTrigger> triggers;
    std::string source;  // "FcChunk0003 line 120": named in errors and trajectory samples
};

// The robot at one instant. Positions [mm], joints [rad].
struct TrajectorySample {
    double t_s = 0;                                         // simulated time (SimClock::now_s)
    SimClock::WallClock::time_point wall;                   // the same instant on the steady clock
    Eigen::Vector3d tcp_base_mm = Eigen::Vector3d::Zero();  // TCP in the base frame
    Eigen::Vector3d tcp_wobj_mm = Eigen::Vector3d::Zero();  // TCP in the segment's work object
    double path_mm = 0;         // TCP arc length travelled since the simulator started
    double speed_mm_s = 0;      // TCP speed
    std::uint64_t segment = 0;  // id of the segment being moved along (0: none yet)
    abb::JointVector joints{};  // linear between the targets' IK solutions [rad]
    std::string source;         // that segment's MotionSegment::source
};

struct MotionOptions {
    abb::Irb1200Variant variant = abb::Irb1200Variant::irb1200_7_70;
    abb::JointSolverOptions solver{.cfx = 1};  // margins; the cfx comes from each target
    double accel_mm_s2 = 1000;                 // TCP acceleration and deceleration
    double tick_s = 0.001;                     // simulated step of the motion thread
    // The thread wakes at most this often in real time, taking as many ticks at once as fit (a
    // trigger still fires at its own tick): at a high time scale a tick is microseconds of real
    // time, and 120,000 sleeps a second at 120x took a core from the service it simulates for.
    double min_wake_real_s = 250e-6;
    double record_period_s = 0.01;      // trajectory sample period (simulated); 0 = every tick
    abb::JointVector start_joints{};    // the robot's joints at start-up [rad]
    std::size_t max_samples = 200'000;  // kept until take_trajectory(), then oldest dropped
};

struct MotionStatus {
    bool moving = false;   // a motion is under way: moving, turning, or about to start
    bool stopped = false;  // StopMove in effect
    bool motors_on = true;
    std::size_t pending = 0;      // queued segments not yet finished (the current one included)
    std::uint64_t last_done = 0;  // id of the last segment whose end the robot passed
    std::string error;            // the controller error that stopped motion, if any
    std::uint64_t samples_dropped = 0;  // past MotionOptions::max_samples
};

class MotionSimulator {
  public:
    // Starts the motion thread.
    MotionSimulator(const SimClock& clock, MotionOptions options = {});
    ~MotionSimulator();  // stops the motion thread
    MotionSimulator(const MotionSimulator&) = delete;
    MotionSimulator& operator=(const MotionSimulator&) = delete;

    // Solves the target and appends the segment; returns its id (1, 2, ...). Never blocks: the
    // caller decides how far to run ahead (see pending() and wait()). Throws MotionError.
    std::uint64_t queue(MotionSegment segment);

    // StopMove: decelerate to a standstill on the path, keep the queue. StartMove: go on.
    void stop_move();
    void start_move();
    // ClearPath: drop every queued segment not yet finished (their triggers never fire); the robot
    // must be standing still (after stop_move), otherwise it first stops as for stop_move (and
    // start_move is then needed to go on). The next segment starts where the robot stands.
    void clear_path();
    // Fault knob "motors off": immediate stop, queue dropped, status().error set; queue() throws
    // until motors_on().
    void motors_off(const std::string& why);
    void motors_on();

    MotionStatus status() const;
    // Whether segment `id` is finished: the robot passed its end (a fly-by point) or stands at it
    // (a stop point); a segment dropped by clear_path or motors_off counts as finished.
    bool done(std::uint64_t id) const;
    // Standing still with nothing queued (RAPID \InPos).
    bool in_position() const;
    // Waits until the status changes (a segment finished, the robot stopped or started) or
    // `timeout` (real time) passes. For callers that wait on motion and must also serve their own
    // events (the RAPID task's interrupts).
    void wait(std::chrono::milliseconds timeout) const;

    // The robot at the motion thread's last tick.
    TrajectorySample current() const;
    // CRobT: the robot at the motion thread's last tick as a robtarget of `tool` in `wobj` (the
    // confdata of its joints).
    rapid::Robtarget robtarget(const rapid::ToolData& tool, const rapid::WobjData& wobj) const;
    // Every recorded sample since start-up (or since the last take), oldest first: one every
    // record_period_s while a motion is under way, one at its start, at every segment end and
    // at every standstill. Memory grows until taken: the owner drains it (see max_samples).
    std::vector<TrajectorySample> take_trajectory();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::sim
