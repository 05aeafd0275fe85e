#pragma once
// Arm with an ortho-parallel basis and a spherical wrist (OPW; Brandstötter, Angerer, Hofbaur,
// "An analytical solution of the inverse kinematics problem of industrial serial manipulators
// with an ortho-parallel basis and a spherical wrist", 2014): forward kinematics and the closed
// form inverse with its eight branches. Geometry only: no joint limits and no choice between
// 2*pi-equivalent angles (joint_solver does both). Frames: robot base, tool0 = flange, z out of
// the flange. Lengths [mm], angles [rad].

#include "drivers/abb/kinematics/joint_vector.hpp"

#include <Eigen/Geometry>

#include <array>
#include <optional>

namespace fibrecell::drivers::abb {

// The paper's seven lengths plus the map to controller angles. In the model's zero pose every
// link points up (+z): axis 1 is z, axes 2 and 3 turn about y, the wrist is z-y-z.
struct OpwParameters {
    double a1 = 0;  // axis 1 to axis 2, along x [mm]
    double a2 = 0;  // across the upper arm, axis 3 to the wrist centre [mm] (ABB: -42, wrist above)
    double b = 0;   // sideways (y) offset of the arm plane from axis 1 [mm]
    double c1 = 0;  // base to axis 2, along z [mm]
    double c2 = 0;  // axis 2 to axis 3: the lower arm [mm]
    double c3 = 0;  // axis 3 to the wrist centre, along the upper arm [mm]
    double c4 = 0;  // wrist centre to the flange [mm]
    JointVector offsets{};                       // controller = sign * (model + offset) [rad]
    std::array<int, 6> signs{1, 1, 1, 1, 1, 1};  // controller axis direction vs the model's
};

// A solution's branch, three bits in the order of ABB's cfx (docs/kinematics.md, "Inverse
// kinematics and branches"), so that for the IRB 1200 cfx == branch. Ties (exactly on a
// singularity) count as front / positive.
inline constexpr int branch_count = 8;
inline constexpr int branch_behind_axis1 = 4;      // wrist centre behind axis 1 (shoulder flip)
inline constexpr int branch_behind_lower_arm = 2;  // wrist centre behind the lower arm (elbow down)
inline constexpr int branch_wrist_negative = 1;    // model axis 5 negative (wrist flip)

// tool0 in the base frame [mm] for joints `q` [rad].
Eigen::Isometry3d forward_kinematics(const OpwParameters& p, const JointVector& q);

// Wrist centre (where axes 4, 5, 6 meet) in the base frame [mm] for joints `q`.
Eigen::Vector3d wrist_centre(const OpwParameters& p, const JointVector& q);

// Wrist centre of a tool0 pose: c4 back along the flange z axis [mm].
Eigen::Vector3d wrist_centre(const OpwParameters& p, const Eigen::Isometry3d& tool0);

// Joints [rad] reaching `tool0` (base frame, mm) on one branch (0..7), every angle in (-pi, pi];
// nothing when the wrist centre is out of reach of the arm on that branch. At a wrist
// singularity (axis 5 at 0 or pi) axis 4 is set to 0 and axis 6 takes the whole rotation.
std::optional<JointVector> inverse_kinematics(const OpwParameters& p,
                                              const Eigen::Isometry3d& tool0, int branch);

// All eight branches, indexed by branch.
std::array<std::optional<JointVector>, branch_count> inverse_kinematics(
    const OpwParameters& p, const Eigen::Isometry3d& tool0);

// The branch (0..7) joints `q` lie on.
int branch_of(const OpwParameters& p, const JointVector& q);

// Elbow angle [rad] in (-pi, pi]: the turn from the lower arm to the line axis 3 -> wrist
// centre; 0 = stretched arm (elbow singularity), positive = wrist centre in front of the
// lower arm.
double elbow_angle(const OpwParameters& p, const JointVector& q);

// Controller axis-3 angle [rad] of the stretched arm (IRB 1200-7/0.7: -83.2 deg).
double stretched_arm_joint3(const OpwParameters& p);

// Distance of the wrist centre `wc` [mm] from the line of axis 1 (from the arm plane's trace when
// b != 0): 0 is the shoulder singularity.
double axis1_distance_mm(const OpwParameters& p, const Eigen::Vector3d& wc);

// Axis 2 to wrist centre `wc` [mm] with the arm in front of or behind axis 1.
double shoulder_to_wrist_mm(const OpwParameters& p, const Eigen::Vector3d& wc, bool behind_axis1);

// Reach of the wrist centre from axis 2 [mm]: c2 + sqrt(a2^2 + c3^2) and |c2 - sqrt(...)|.
double max_wrist_reach_mm(const OpwParameters& p);
double min_wrist_reach_mm(const OpwParameters& p);

}  // namespace fibrecell::drivers::abb
