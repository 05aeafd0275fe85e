#pragma once
// Joints for a print: one cfx branch for the whole print, the 2*pi-equivalents of the multi-turn
// axes nearest to the previous joints (J4, J6 wound continuously), then the checks the
// controller would fail on or struggle near: joint limits, wrist, elbow and shoulder
// singularities, each with a margin. See docs/kinematics.md.

#include "drivers/abb/kinematics/confdata.hpp"
#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/abb/kinematics/tool_frames.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::abb {

struct JointSolverOptions {
    int cfx = 0;                     // branch for the whole print; 0 = front, elbow up, J5 > 0
    double limit_margin_deg = 2;     // kept inside every joint range
    double wrist_margin_deg = 5;     // |J5| at least this (J5 = 0 is the wrist singularity)
    double elbow_margin_deg = 5;     // J3 at least this far from the stretched arm (-83.2 deg)
    double shoulder_margin_mm = 50;  // wrist centre at least this far from the axis-1 line
};

enum class IkFailureKind {
    none,
    out_of_reach,          // wrist centre farther from (or nearer to) axis 2 than the arm reaches
    shoulder_singularity,  // wrist centre near the axis-1 line
    joint_limit,           // a joint outside its range less the margin
    wrist_singularity,     // J5 near 0
    elbow_singularity,     // J3 near the stretched arm
};

std::string_view to_string(IkFailureKind k);

struct IkFailure {
    IkFailureKind kind = IkFailureKind::none;
    int axis = 0;        // 1..6 for joint failures, 0 otherwise
    double value = 0;    // the offending joint [deg] or distance [mm]
    std::string reason;  // "joint 5 at 1.2 deg is within the 5 deg wrist-singularity margin"
};

struct IkResult {
    JointVector joints{};  // [rad], valid when ok(); also set for joint failures
    ConfData conf;         // of `joints`
    IkFailure failure;
    bool ok() const { return failure.kind == IkFailureKind::none; }
};

// The 2*pi-equivalent of each joint of `q` to use after `reference` [rad]: for an axis whose range
// spans a full turn or more, the one nearest to the reference (continuous motion: a wind-up past
// the limit is then reported, not jumped back); for a shorter range the one inside it, if any.
JointVector unwrap_joints(const JointLimits& limits, const JointVector& q,
                          const JointVector& reference);

// Joints putting tool0 at `tool0_in_base` [mm] on branch `options.cfx`, unwrapped against
// `reference` (the previous joints, or the current ones for a first target) [rad].
// Throws std::invalid_argument when options.cfx is not 0..7.
IkResult solve_tool0(const RobotModel& robot, const Eigen::Isometry3d& tool0_in_base,
                     const JointVector& reference, const JointSolverOptions& options = {});

// Joints putting the TCP of `frames.tool` at `tcp_in_work_object` [mm].
IkResult solve_tcp(const RobotModel& robot, const TcpFrames& frames,
                   const Eigen::Isometry3d& tcp_in_work_object, const JointVector& reference,
                   const JointSolverOptions& options = {});

struct PathSolution {
    std::vector<IkResult> points;  // one per target, in order, up to the first failure
    IkFailure failure;             // of target points.size(); kind none when all were solved
    bool ok() const { return failure.kind == IkFailureKind::none; }
};

// A sequence of TCP targets, each unwrapped against the previous one, from joints `start` [rad].
PathSolution solve_path(const RobotModel& robot, const TcpFrames& frames,
                        std::span<const Eigen::Isometry3d> tcp_in_work_object,
                        const JointVector& start, const JointSolverOptions& options = {});

}  // namespace fibrecell::drivers::abb
