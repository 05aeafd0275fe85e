#include "drivers/abb/kinematics/joint_solver.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace fibrecell::drivers::abb {
namespace {

constexpr double two_pi = 2 * std::numbers::pi;

// Measured values with one decimal ("83.2"), settings as given ("5", "2.5").
std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

std::string setting(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string axis_name(int axis) {
    return "joint " + std::to_string(axis);
}

// Angular distance from the nearest multiple of pi [rad]: both 0 and pi are singular.
double from_singular(double a) {
    const double r = std::abs(wrap_to_pi(a));
    return std::min(r, std::numbers::pi - r);
}

IkResult failed(IkResult r, IkFailureKind kind, int axis, double value, std::string reason) {
    r.failure = {kind, axis, value, std::move(reason)};
    return r;
}

}  // namespace

std::string_view to_string(IkFailureKind k) {
    switch (k) {
        case IkFailureKind::none:
            return "none";
        case IkFailureKind::out_of_reach:
            return "out_of_reach";
        case IkFailureKind::shoulder_singularity:
            return "shoulder_singularity";
        case IkFailureKind::joint_limit:
            return "joint_limit";
        case IkFailureKind::wrist_singularity:
            return "wrist_singularity";
        case IkFailureKind::elbow_singularity:
            return "elbow_singularity";
    }
    return "unknown";
}

JointVector unwrap_joints(const JointLimits& limits, const JointVector& q,
                          const JointVector& reference) {
    JointVector out = q;
    for (int i = 0; i < 6; ++i) {
        const double lo = limits.lower_rad[i], hi = limits.upper_rad[i];
        out[i] = nearest_turn(q[i], reference[i]);
        if (hi - lo >= two_pi) continue;
        // Less than a turn: at most one equivalent fits; the reference only breaks the tie
        // when none does (the limit check then names it).
        const double inside = q[i] + two_pi * std::ceil((lo - q[i]) / two_pi - 1e-12);
        if (inside <= hi + 1e-12) out[i] = inside;
    }
    return out;
}

IkResult solve_tool0(const RobotModel& robot, const Eigen::Isometry3d& tool0_in_base,
                     const JointVector& reference, const JointSolverOptions& options) {
    if (options.cfx < 0 || options.cfx >= branch_count)
        throw std::invalid_argument("cfx must be 0..7, got " + std::to_string(options.cfx));
    const OpwParameters& g = robot.geometry;
    IkResult r;

    const auto raw = inverse_kinematics(g, tool0_in_base, options.cfx);
    const Eigen::Vector3d wc = wrist_centre(g, tool0_in_base);
    if (!raw) {
        const double s = shoulder_to_wrist_mm(g, wc, (options.cfx & branch_behind_axis1) != 0);
        const bool far = s > max_wrist_reach_mm(g);
        return failed(r, IkFailureKind::out_of_reach, 0, s,
                      "out of reach: wrist centre " + num(s) + " mm from the shoulder, " +
                          (far ? "at most " + num(max_wrist_reach_mm(g))
                               : "at least " + num(min_wrist_reach_mm(g))));
    }
    const double axis1_mm = axis1_distance_mm(g, wc);
    if (axis1_mm < options.shoulder_margin_mm)
        return failed(r, IkFailureKind::shoulder_singularity, 0, axis1_mm,
                      "wrist centre " + num(axis1_mm) + " mm from the axis-1 line, within the " +
                          setting(options.shoulder_margin_mm) + " mm shoulder-singularity margin");

    r.joints = unwrap_joints(robot.limits, *raw, reference);
    r.conf = {quadrant(r.joints[0]), quadrant(r.joints[3]), quadrant(r.joints[5]), options.cfx};

    const double margin = deg_to_rad(options.limit_margin_deg);
    for (int i = 0; i < 6; ++i) {
        const double lo = robot.limits.lower_rad[i], hi = robot.limits.upper_rad[i];
        if (r.joints[i] >= lo + margin && r.joints[i] <= hi - margin) continue;
        return failed(r, IkFailureKind::joint_limit, i + 1, rad_to_deg(r.joints[i]),
                      axis_name(i + 1) + " at " + num(rad_to_deg(r.joints[i])) +
                          " deg is outside " + num(rad_to_deg(lo + margin)) + ".." +
                          num(rad_to_deg(hi - margin)) + " deg (its range " + num(rad_to_deg(lo)) +
                          ".." + num(rad_to_deg(hi)) + " less the " +
                          setting(options.limit_margin_deg) + " deg margin)");
    }

    const double t5 = g.signs[4] * r.joints[4] - g.offsets[4];
    if (from_singular(t5) < deg_to_rad(options.wrist_margin_deg))
        return failed(r, IkFailureKind::wrist_singularity, 5, rad_to_deg(r.joints[4]),
                      "joint 5 at " + num(rad_to_deg(r.joints[4])) + " deg is within the " +
                          setting(options.wrist_margin_deg) + " deg wrist-singularity margin");

    const double elbow = elbow_angle(g, r.joints);
    if (from_singular(elbow) < deg_to_rad(options.elbow_margin_deg)) {
        // The singular J3 nearest to this one: stretched (elbow 0) or folded (elbow pi).
        const double singular = stretched_arm_joint3(g) +
                                (std::abs(elbow) < std::numbers::pi / 2 ? 0 : std::numbers::pi);
        return failed(r, IkFailureKind::elbow_singularity, 3, rad_to_deg(r.joints[2]),
                      "joint 3 at " + num(rad_to_deg(r.joints[2])) + " deg is within the " +
                          setting(options.elbow_margin_deg) + " deg elbow-singularity margin of " +
                          num(rad_to_deg(nearest_turn(singular, r.joints[2]))) + " deg");
    }
    return r;
}

IkResult solve_tcp(const RobotModel& robot, const TcpFrames& frames,
                   const Eigen::Isometry3d& tcp_in_work_object, const JointVector& reference,
                   const JointSolverOptions& options) {
    return solve_tool0(robot, tool0_for_tcp(frames, tcp_in_work_object), reference, options);
}

PathSolution solve_path(const RobotModel& robot, const TcpFrames& frames,
                        std::span<const Eigen::Isometry3d> tcp_in_work_object,
                        const JointVector& start, const JointSolverOptions& options) {
    PathSolution path;
    path.points.reserve(tcp_in_work_object.size());
    JointVector previous = start;
    for (const Eigen::Isometry3d& tcp : tcp_in_work_object) {
        IkResult r = solve_tcp(robot, frames, tcp, previous, options);
        if (!r.ok()) {
            path.failure = std::move(r.failure);
            break;
        }
        previous = r.joints;
        path.points.push_back(std::move(r));
    }
    return path;
}

}  // namespace fibrecell::drivers::abb
