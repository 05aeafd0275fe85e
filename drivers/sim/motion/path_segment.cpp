#include "drivers/sim/motion/path_segment.hpp"

#include "drivers/abb/kinematics/confdata.hpp"
#include "drivers/abb/kinematics/opw_kinematics.hpp"

#include <algorithm>

namespace fibrecell::drivers::sim {
namespace {

// Below these a move has no length / no turn: the pose it starts from is a previous target's
// pose recomputed through the tool, equal to the target up to rounding.
constexpr double min_length_mm = 1e-6;
constexpr double min_turn_rad = 1e-9;

Eigen::Isometry3d to_isometry(const Eigen::Vector3d& trans_mm, const Eigen::Quaterniond& rot) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = rot.normalized().toRotationMatrix();
    t.translation() = trans_mm;
    return t;
}

bool valid(const Eigen::Vector3d& trans_mm, const Eigen::Quaterniond& rot) {
    return trans_mm.allFinite() && rot.coeffs().allFinite() && rot.norm() > 1e-6;
}

abb::ConfData to_abb(const rapid::ConfData& c) {
    return {.cf1 = c.cf1, .cf4 = c.cf4, .cf6 = c.cf6, .cfx = c.cfx};
}

// The branch a linear move starts on must be the target's: a straight TCP line crosses no
// singularity. Joints exactly on the wrist singularity (J5 = 0, as the all-zero start joints)
// belong to both wrist branches.
bool same_arm_configuration(const abb::RobotModel& robot, const abb::JointVector& from, int cfx) {
    const int changed = abb::branch_of(robot.geometry, from) ^ cfx;
    return changed == 0 || (changed == abb::branch_wrist_negative && from[4] == 0);
}

}  // namespace

double PathSegment::fraction(double position_mm, double dwell_elapsed_s) const {
    if (reorientation()) return std::clamp(dwell_elapsed_s / dwell_s, 0.0, 1.0);
    return length_mm > 0 ? std::clamp(position_mm / length_mm, 0.0, 1.0) : 1.0;
}

RobotPose PathSegment::pose_at(double f) const {
    RobotPose pose{.tool = tool,
                   .wobj = wobj,
                   .path_mm = path_start_mm + f * length_mm,
                   .segment = id,
                   .source = source};
    pose.tcp = to_isometry(start_mm + f * (end_mm - start_mm), start_rot.slerp(f, end_rot));
    for (std::size_t i = 0; i < pose.joints.size(); ++i)
        pose.joints[i] = start_joints[i] + f * (end_joints[i] - start_joints[i]);
    return pose;
}

void PathSegment::truncate(double new_length_mm) {
    if (reorientation() || !(new_length_mm < length_mm)) return;
    const double f = std::max(0.0, new_length_mm) / length_mm;
    end_joints = pose_at(f).joints;
    end_mm = start_mm + f * (end_mm - start_mm);
    end_rot = start_rot.slerp(f, end_rot);
    turn_rad *= f;
    length_mm *= f;
}

PathSegment solve_segment(const MotionSegment& move, const RobotPose& from,
                          const abb::RobotModel& robot, const abb::JointSolverOptions& solver) {
    auto error = [&](const std::string& why) { return MotionError(move.source + ": " + why); };
    const rapid::Robtarget& target = move.target;
    const rapid::WobjData& w = move.wobj;
    if (!valid(target.trans_mm, target.rot) ||
        !valid(move.tool.tframe.trans_mm, move.tool.tframe.rot) ||
        !valid(w.uframe.trans_mm, w.uframe.rot) || !valid(w.oframe.trans_mm, w.oframe.rot))
        throw error("target, tool or work object has a non-finite position or a zero quaternion");
    const int cfx = target.conf.cfx;
    if (cfx < 0 || cfx >= abb::branch_count)
        throw error("cfx " + std::to_string(cfx) + " is not 0..7");

    PathSegment seg{.source = move.source, .stop_point = move.zone.finep};
    seg.tool = tool_frame(move.tool);
    seg.wobj = wobj_frame(w);
    const Eigen::Isometry3d target_in_wobj = to_isometry(target.trans_mm, target.rot);

    abb::JointSolverOptions options = solver;
    options.cfx = cfx;
    const abb::IkResult ik = abb::solve_tcp(robot, {.tool = seg.tool, .work_object = seg.wobj},
                                            target_in_wobj, from.joints, options);
    if (!ik.ok())
        throw error("target unreachable on cfx " + std::to_string(cfx) + ": " + ik.failure.reason);
    const abb::ConfData wanted = to_abb(target.conf);
    if (move.joint ? !(ik.conf == wanted) : ik.conf.cfx != cfx)
        throw error("the solution's confdata " + abb::to_string(ik.conf) +
                    " does not match the target's " + abb::to_string(wanted));
    if (!move.joint && !same_arm_configuration(robot, from.joints, cfx))
        throw error("a linear move cannot change the arm configuration: cfx " +
                    std::to_string(abb::branch_of(robot.geometry, from.joints)) +
                    " at its start, " + std::to_string(cfx) + " at the target");

    const Eigen::Isometry3d start = from.flange() * seg.tool;
    const Eigen::Isometry3d end = seg.wobj * target_in_wobj;
    seg.start_mm = start.translation();
    seg.end_mm = end.translation();
    seg.start_rot = Eigen::Quaterniond(start.linear());
    seg.end_rot = Eigen::Quaterniond(end.linear());
    seg.start_joints = from.joints;
    seg.end_joints = ik.joints;
    seg.path_start_mm = from.path_mm;

    const double length = (seg.end_mm - seg.start_mm).norm();
    const double turn = seg.start_rot.angularDistance(seg.end_rot);
    const double turn_deg = abb::rad_to_deg(turn);
    const double v_tcp = move.speed.v_tcp_mm_s, v_ori = move.speed.v_ori_deg_s;
    seg.turn_rad = turn > min_turn_rad ? turn : 0;
    if (seg.turn_rad > 0 && !(v_ori > 0))
        throw error("speed v_ori must be positive for a move that turns the tool");
    if (length > min_length_mm) {
        if (!(v_tcp > 0)) throw error("speed v_tcp must be positive");
        seg.length_mm = length;
        // The slower of the line at v_tcp and the turn at v_ori sets the pace.
        seg.cruise_mm_s = seg.turn_rad > 0 ? std::min(v_tcp, length * v_ori / turn_deg) : v_tcp;
    } else if (seg.turn_rad > 0) {
        seg.dwell_s = turn_deg / v_ori;
    }

    for (const MotionTrigger& t : move.triggers) {
        const double d = std::clamp(t.distance_mm, 0.0, seg.length_mm);
        seg.triggers.push_back({.trigger = t,
                                .position_mm = t.from_start ? d : seg.length_mm - d,
                                .at_start = t.from_start});
    }
    std::stable_sort(seg.triggers.begin(), seg.triggers.end(),
                     [](const PlacedTrigger& a, const PlacedTrigger& b) {
                         return a.position_mm < b.position_mm ||
                                (a.position_mm == b.position_mm && a.at_start && !b.at_start);
                     });
    return seg;
}

Eigen::Isometry3d tool_frame(const rapid::ToolData& tool) {
    return to_isometry(tool.tframe.trans_mm, tool.tframe.rot);
}

Eigen::Isometry3d wobj_frame(const rapid::WobjData& wobj) {
    return to_isometry(wobj.uframe.trans_mm, wobj.uframe.rot) *
           to_isometry(wobj.oframe.trans_mm, wobj.oframe.rot);
}

rapid::Robtarget robtarget_of(const RobotPose& pose, const rapid::ToolData& tool,
                              const rapid::WobjData& wobj, const abb::OpwParameters& geometry) {
    const Eigen::Isometry3d tcp = wobj_frame(wobj).inverse(Eigen::Isometry) * pose.flange() *
                                  tool_frame(tool);
    const abb::ConfData c = abb::confdata(geometry, pose.joints);
    return {.trans_mm = tcp.translation(),
            .rot = Eigen::Quaterniond(tcp.linear()),
            .conf = {.cf1 = c.cf1, .cf4 = c.cf4, .cf6 = c.cf6, .cfx = c.cfx}};
}

}  // namespace fibrecell::drivers::sim
