#pragma once
// One queued move, solved and laid out in the base frame: the straight TCP line, the orientation
// turn, the joints at both ends and the speed it is moved at (docs/sim-motion.md).

#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "drivers/abb/kinematics/joint_vector.hpp"
#include "drivers/sim/motion/motion_simulator.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

// Where the robot stands, or will stand once the queued motion is done: where the next move
// starts.
struct RobotPose {
    Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();   // TCP in base [mm]
    abb::JointVector joints{};                               // [rad]
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  // tool0 -> TCP of the last move
    Eigen::Isometry3d wobj = Eigen::Isometry3d::Identity();  // base -> its work object
    double path_mm = 0;                                      // TCP arc length travelled up to here
    std::uint64_t segment = 0;                               // the last move (0: none yet)
    std::string source;

    Eigen::Isometry3d flange() const { return tcp * tool.inverse(Eigen::Isometry); }  // tool0
};

// A trigger placed on its segment.
struct PlacedTrigger {
    MotionTrigger trigger;
    double position_mm = 0;  // along the segment (clamped to it)
    bool at_start = false;   // on a pure reorientation: fire as it starts, not as it ends
    bool fired = false;
};

struct PathSegment {
    std::uint64_t id = 0;
    std::string source;
    bool stop_point = false;  // fine
    bool cleared = false;     // dropped by ClearPath: only braked along, its triggers removed
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  // tool0 -> TCP
    Eigen::Isometry3d wobj = Eigen::Isometry3d::Identity();  // base -> work object
    Eigen::Vector3d start_mm = Eigen::Vector3d::Zero();      // TCP in base
    Eigen::Vector3d end_mm = Eigen::Vector3d::Zero();
    Eigen::Quaterniond start_rot = Eigen::Quaterniond::Identity();  // TCP orientation in base
    Eigen::Quaterniond end_rot = Eigen::Quaterniond::Identity();
    abb::JointVector start_joints{};  // [rad]
    abb::JointVector end_joints{};
    double path_start_mm = 0;             // path_mm at its start
    double length_mm = 0;                 // 0: a pure reorientation or a no-op
    double turn_rad = 0;                  // orientation change
    double cruise_mm_s = 0;               // v_tcp, or slower when v_ori limits the turn
    double dwell_s = 0;                   // a pure reorientation: turn / v_ori
    std::vector<PlacedTrigger> triggers;  // by position

    bool reorientation() const { return dwell_s > 0; }
    double path_end_mm() const { return path_start_mm + length_mm; }
    // 0..1 along the segment for a robot at `position_mm` [mm] (a reorientation: by time done).
    double fraction(double position_mm, double dwell_elapsed_s) const;
    // The robot at `fraction` 0..1 of the segment: positions and the slerped orientation
    // linear in it, joints too.
    RobotPose pose_at(double fraction) const;
    // Ends the segment `length_mm` [mm] after its start (where ClearPath leaves the robot).
    void truncate(double length_mm);
};

// Solves `move` from `from` (the end of the previous move, or where the robot stands): IK on the
// target's cfx branch with `solver`'s margins against `from.joints`, the confdata check (cf1, cf4,
// cf6 and cfx for a joint move; for a linear move the cfx, which a straight line cannot change),
// the speed, the triggers' positions. `path_start_mm` of the result is from.path_mm. Throws
// MotionError "<source>: <reason>".
PathSegment solve_segment(const MotionSegment& move, const RobotPose& from,
                          const abb::RobotModel& robot, const abb::JointSolverOptions& solver);

// The frames of RAPID tool and work object data: tool0 -> TCP, base -> object frame [mm].
Eigen::Isometry3d tool_frame(const rapid::ToolData& tool);
Eigen::Isometry3d wobj_frame(const rapid::WobjData& wobj);

// CRobT: the robot at `pose` as a robtarget of `tool` in `wobj`, with the confdata of its joints.
// Any tool will do: its TCP is computed from the flange where the robot stands.
rapid::Robtarget robtarget_of(const RobotPose& pose, const rapid::ToolData& tool,
                              const rapid::WobjData& wobj, const abb::OpwParameters& geometry);

}  // namespace fibrecell::drivers::sim
