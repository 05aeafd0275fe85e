#include "drivers/abb/kinematics/confdata.hpp"
#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "drivers/abb/kinematics/opw_kinematics.hpp"
#include "drivers/abb/kinematics/tool_frames.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace fibrecell::drivers::abb;
namespace abb = fibrecell::drivers::abb;

namespace {

JointVector deg(const JointVector& d) {
    JointVector r;
    for (int i = 0; i < 6; ++i) r[i] = deg_to_rad(d[i]);
    return r;
}

Eigen::Matrix3d rot_y_deg(double a) {
    return Eigen::AngleAxisd(deg_to_rad(a), Eigen::Vector3d::UnitY()).toRotationMatrix();
}

Eigen::Matrix3d rot_z_deg(double a) {
    return Eigen::AngleAxisd(deg_to_rad(a), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Isometry3d pose(const Eigen::Vector3d& p_mm, const Eigen::Matrix3d& r) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = r;
    t.translation() = p_mm;
    return t;
}

void expect_pose_near(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double mm = 1e-6,
                      double rot = 1e-9) {
    EXPECT_LT((a.translation() - b.translation()).norm(), mm)
        << a.translation().transpose() << " vs " << b.translation().transpose();
    EXPECT_LT((a.linear() - b.linear()).norm(), rot);
}

// Angular distance from the nearest multiple of pi.
double from_singular(double a) {
    const double r = std::abs(wrap_to_pi(a));
    return std::min(r, std::numbers::pi - r);
}

// Uniform joints inside the limits shrunk by `limit_deg`, at least `singular_deg` from the wrist
// and elbow singularities and `shoulder_mm` from the axis-1 line.
JointVector random_joints(std::mt19937& rng, const RobotModel& m, double limit_deg,
                          double singular_deg, double shoulder_mm) {
    for (;;) {
        JointVector q;
        for (int i = 0; i < 6; ++i) {
            const double margin = deg_to_rad(limit_deg);
            std::uniform_real_distribution<double> d(m.limits.lower_rad[i] + margin,
                                                     m.limits.upper_rad[i] - margin);
            q[i] = d(rng);
        }
        if (from_singular(q[4]) < deg_to_rad(singular_deg)) continue;
        if (from_singular(elbow_angle(m.geometry, q)) < deg_to_rad(singular_deg)) continue;
        if (axis1_distance_mm(m.geometry, wrist_centre(m.geometry, q)) < shoulder_mm) continue;
        return q;
    }
}

}  // namespace

// docs/kinematics.md, "Frames and conventions": tool0 at zero joints, quaternion [w, x, y, z] =
// [0.7071, 0, 0.7071, 0] (tool0 z along base +X, x along base -Z).
TEST(Irb1200Kinematics, ForwardAtZeroJoints) {
    const JointVector zero{};
    const Eigen::Isometry3d a = forward_kinematics(irb1200().geometry, zero);
    EXPECT_NEAR((a.translation() - Eigen::Vector3d(433, 0, 791.1)).norm(), 0, 1e-9);
    const Eigen::Isometry3d b =
        forward_kinematics(irb1200(Irb1200Variant::irb1200_5_90).geometry, zero);
    EXPECT_NEAR((b.translation() - Eigen::Vector3d(533, 0, 889.1)).norm(), 0, 1e-9);
    for (const Eigen::Isometry3d& t : {a, b}) {
        const Eigen::Quaterniond q(t.linear());
        const double s = q.w() < 0 ? -1 : 1;  // q and -q are the same rotation
        EXPECT_NEAR(s * q.w(), std::sqrt(0.5), 1e-12);
        EXPECT_NEAR(s * q.x(), 0, 1e-12);
        EXPECT_NEAR(s * q.y(), std::sqrt(0.5), 1e-12);
        EXPECT_NEAR(s * q.z(), 0, 1e-12);
        EXPECT_NEAR(t.linear().col(2).x(), 1, 1e-12);   // tool0 z along base +X
        EXPECT_NEAR(t.linear().col(0).z(), -1, 1e-12);  // tool0 x along base -Z
    }
}

// Hand-computed from the URDF chain (docs/kinematics.md, "Sources"; 7/0.7: J1 z 399.1,
// J3 z 350, J4 z 42, J5 x 351, J6 x 82, tool0 = Ry(+90 deg) of the flange):
// * J2 = +90: Ry(90) maps z to +x and x to -z, so J3 sits at (350, 0, 399.1), J4 at
//   (350 + 42, 0, 399.1), J5 at (392, 0, 399.1 - 351), the flange at (392, 0, 48.1 - 82) =
//   (392, 0, -33.9); tool0 = Ry(90) Ry(90) = Ry(180): z down.
// * J3 = -90: Ry(-90) maps z to -x and x to +z: J4 at (-42, 0, 749.1), J5 at (-42, 0, 1100.1),
//   flange at (-42, 0, 1182.1); tool0 = Ry(-90) Ry(90) = identity: z up.
// * J1 = 90, J5 = 90: the zero pose's wrist centre (351, 0, 791.1) turned to (0, 351, 791.1);
//   J5 pitches the flange down: tool0 at (0, 351, 709.1), rotation Rz(90) Ry(180).
TEST(Irb1200Kinematics, ForwardAtHandComputedPoses) {
    const OpwParameters g = irb1200().geometry;
    expect_pose_near(forward_kinematics(g, deg({0, 90, 0, 0, 0, 0})),
                     pose({392, 0, -33.9}, rot_y_deg(180)), 1e-9);
    expect_pose_near(forward_kinematics(g, deg({0, 0, -90, 0, 0, 0})),
                     pose({-42, 0, 1182.1}, Eigen::Matrix3d::Identity()), 1e-9);
    expect_pose_near(forward_kinematics(g, deg({90, 0, 0, 0, 90, 0})),
                     pose({0, 351, 709.1}, rot_z_deg(90) * rot_y_deg(180)), 1e-9);
    EXPECT_NEAR((wrist_centre(g, deg({0, 90, 0, 0, 0, 0})) - Eigen::Vector3d(392, 0, 48.1)).norm(),
                0, 1e-9);
}

// docs/kinematics.md, "Sources": stretched arm at J3 = -atan2(c3, 42); reach to the wrist centre
// c2 + |(c3, a2)|.
TEST(Irb1200Kinematics, SanityNumbers) {
    const OpwParameters a = irb1200().geometry;
    const OpwParameters b = irb1200(Irb1200Variant::irb1200_5_90).geometry;
    EXPECT_NEAR(rad_to_deg(stretched_arm_joint3(a)), -83.18, 0.01);
    EXPECT_NEAR(rad_to_deg(stretched_arm_joint3(b)), -84.68, 0.01);
    EXPECT_NEAR(max_wrist_reach_mm(a), 703.5, 0.05);
    EXPECT_NEAR(max_wrist_reach_mm(b), 901.0, 0.05);
    EXPECT_EQ(parse_irb1200_variant("5/0.9"), Irb1200Variant::irb1200_5_90);
    EXPECT_EQ(parse_irb1200_variant("IRB 1200-7/0.7"), Irb1200Variant::irb1200_7_70);
    EXPECT_EQ(parse_irb1200_variant("irb1200_5_90"), Irb1200Variant::irb1200_5_90);
    EXPECT_FALSE(parse_irb1200_variant("7/0.9"));
}

// Every returned branch maps back to the pose and is tagged with the branch its joints lie on;
// the branch of q itself returns q (mod 2*pi: the raw solver wraps to (-pi, pi]).
TEST(Irb1200Kinematics, InverseOfForwardOnEveryBranch) {
    std::mt19937 rng(1200);
    for (const auto variant : {Irb1200Variant::irb1200_7_70, Irb1200Variant::irb1200_5_90}) {
        const RobotModel m = irb1200(variant);
        std::array<int, branch_count> seen{};
        for (int n = 0; n < 1200; ++n) {
            const JointVector q = random_joints(rng, m, 0, 0.5, 5);
            const Eigen::Isometry3d t = forward_kinematics(m.geometry, q);
            const int own = branch_of(m.geometry, q);
            ++seen[own];
            const auto all = inverse_kinematics(m.geometry, t);
            ASSERT_TRUE(all[own]) << m.name << " sample " << n;
            for (int i = 0; i < 6; ++i)
                ASSERT_NEAR(wrap_to_pi((*all[own])[i] - q[i]), 0, 1e-9)
                    << m.name << " sample " << n << " joint " << i + 1;
            for (int b = 0; b < branch_count; ++b) {
                ASSERT_TRUE(all[b]) << "a1 = b = 0: every branch reaches what one reaches";
                ASSERT_EQ(branch_of(m.geometry, *all[b]), b) << "sample " << n;
                const Eigen::Isometry3d back = forward_kinematics(m.geometry, *all[b]);
                ASSERT_LT((back.translation() - t.translation()).norm(), 1e-6);
                ASSERT_LT((back.linear() - t.linear()).norm(), 1e-9);
            }
        }
        for (int b = 0; b < branch_count; ++b)
            EXPECT_GT(seen[b], 40) << m.name << ": too few samples on cfx " << b;
    }
}

TEST(Irb1200Kinematics, SingularWristStillMapsBack) {
    const OpwParameters g = irb1200().geometry;
    const Eigen::Isometry3d t = forward_kinematics(g, deg({10, 20, -30, 40, 0, 50}));
    for (const auto& q : inverse_kinematics(g, t)) {
        ASSERT_TRUE(q);
        expect_pose_near(forward_kinematics(g, *q), t);
    }
    // Axis 4 is set to 0 and axis 6 takes 40 + 50 deg on the J5 >= 0 branch.
    const JointVector q0 = *inverse_kinematics(g, t, 0);
    EXPECT_NEAR(q0[3], 0, 1e-12);
    EXPECT_NEAR(rad_to_deg(q0[5]), 90, 1e-6);
}

TEST(Irb1200Kinematics, OutOfReachHasNoSolution) {
    const OpwParameters g = irb1200().geometry;
    const Eigen::Isometry3d far = pose({900, 0, 500}, rot_y_deg(180));
    for (const auto& q : inverse_kinematics(g, far)) EXPECT_FALSE(q);
}

// Hand-worked (7/0.7). x_w: wrist centre along the arm plane's forward axis (in front of axis 1
// when > 0), elbow = J3 + 90 - 6.83 deg (in front of the lower arm when > 0), then J5's sign.
TEST(Irb1200Confdata, HandWorkedJointVectors) {
    const OpwParameters g = irb1200().geometry;
    EXPECT_EQ(quadrant(deg_to_rad(-0.1)), -1);
    EXPECT_EQ(quadrant(0), 0);
    EXPECT_EQ(quadrant(deg_to_rad(89.9)), 0);
    EXPECT_EQ(quadrant(deg_to_rad(90)), 1);
    EXPECT_EQ(quadrant(deg_to_rad(-90)), -1);
    EXPECT_EQ(quadrant(deg_to_rad(-90.1)), -2);
    EXPECT_EQ(quadrant(deg_to_rad(359)), 3);
    EXPECT_EQ(quadrant(deg_to_rad(-270)), -3);
    // Zero pose: x_w = 351 in front, elbow 83.2 in front, J5 = 0 counts as positive.
    EXPECT_EQ(confdata(g, {}), (abb::ConfData{0, 0, 0, 0}));
    // Same arm, J1 -0.1 (quadrant -1), J4 90 (1), J6 -190 (-3), J5 -30: cfx 1.
    EXPECT_EQ(confdata(g, deg({-0.1, 0, 0, 90, -30, -190})), (abb::ConfData{-1, 1, -3, 1}));
    // J2 60, J3 -120: x_w = 350 sin 60 - 42 cos 30 + 351 sin 30 = 303.1 - 36.4 + 175.5 = 442.2
    // in front; elbow -30 - 6.8 = -36.8 behind the lower arm: cfx 2 (J5 20) or 3 (J5 -20).
    EXPECT_EQ(confdata(g, deg({45, 60, -120, -45, 20, 100})), (abb::ConfData{0, -1, 1, 2}));
    EXPECT_EQ(confdata(g, deg({45, 60, -120, -45, -20, 100})), (abb::ConfData{0, -1, 1, 3}));
    // J2 -90: lower arm level backwards, upper arm up: x_w = -350 - 42 = -392 behind axis 1,
    // elbow 83.2 in front of the lower arm: cfx 4 (J5 20) or 5 (J5 -20).
    EXPECT_EQ(confdata(g, deg({-100, -90, 0, 269, 20, 359})), (abb::ConfData{-2, 2, 3, 4}));
    EXPECT_EQ(confdata(g, deg({-100, -90, 0, 269, -20, 359})), (abb::ConfData{-2, 2, 3, 5}));
    // J3 -120 at J2 0: x_w = -42 cos 30 - 351 sin 30 = -211.9 behind, elbow -36.8 behind: 6, 7.
    EXPECT_EQ(confdata(g, deg({0, 0, -120, 0, 20, 0})).cfx, 6);
    EXPECT_EQ(confdata(g, deg({0, 0, -120, 0, -20, 0})).cfx, 7);
    EXPECT_EQ(to_string(abb::ConfData{0, -1, 2, 5}), "[0,-1,2,5]");
}

// With reference joints near q, the solver returns q itself (no wrap) on q's own branch.
TEST(Irb1200JointSolver, ReturnsTheJointsOnTheChosenBranch) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(-0.5, 0.5);
    const JointSolverOptions defaults;
    for (const auto variant : {Irb1200Variant::irb1200_7_70, Irb1200Variant::irb1200_5_90}) {
        const RobotModel m = irb1200(variant);
        for (int n = 0; n < 1000; ++n) {
            const JointVector q =
                random_joints(rng, m, defaults.limit_margin_deg + 0.01,
                              defaults.wrist_margin_deg + 0.01, defaults.shoulder_margin_mm + 0.01);
            if (from_singular(elbow_angle(m.geometry, q)) <
                deg_to_rad(defaults.elbow_margin_deg + 0.01))
                continue;
            JointVector reference = q;
            for (double& r : reference) r += noise(rng);
            JointSolverOptions o;
            o.cfx = branch_of(m.geometry, q);
            const IkResult r = solve_tool0(m, forward_kinematics(m.geometry, q), reference, o);
            ASSERT_TRUE(r.ok()) << m.name << " sample " << n << ": " << r.failure.reason;
            for (int i = 0; i < 6; ++i) ASSERT_NEAR(r.joints[i], q[i], 1e-9) << "joint " << i + 1;
            ASSERT_EQ(r.conf, confdata(m.geometry, q));
        }
    }
}

TEST(Irb1200JointSolver, ReportsWhyATargetFails) {
    const RobotModel m = irb1200();
    const OpwParameters& g = m.geometry;
    const JointVector home{};

    // Tool down at (900, 0, 500): wrist centre (900, 0, 582), from the shoulder (0, 0, 399.1):
    // sqrt(900^2 + 182.9^2) = 918.4 mm.
    const IkResult far = solve_tool0(m, pose({900, 0, 500}, rot_y_deg(180)), home);
    EXPECT_EQ(far.failure.kind, IkFailureKind::out_of_reach);
    EXPECT_EQ(far.failure.reason,
              "out of reach: wrist centre 918.4 mm from the shoulder, at most 703.5");

    const IkResult wrist =
        solve_tool0(m, forward_kinematics(g, deg({0, 10, -10, 0, 1.2, 0})), home);
    EXPECT_EQ(wrist.failure.kind, IkFailureKind::wrist_singularity);
    EXPECT_EQ(wrist.failure.axis, 5);
    EXPECT_EQ(wrist.failure.reason,
              "joint 5 at 1.2 deg is within the 5 deg wrist-singularity margin");

    const IkResult limit =
        solve_tool0(m, forward_kinematics(g, deg({169, 10, 10, 0, 60, 0})), home);
    EXPECT_EQ(limit.failure.kind, IkFailureKind::joint_limit);
    EXPECT_EQ(limit.failure.axis, 1);
    EXPECT_NEAR(limit.failure.value, 169, 1e-9);
    EXPECT_EQ(limit.failure.reason,
              "joint 1 at 169.0 deg is outside -168.0..168.0 deg (its range -170.0..170.0 less "
              "the 2 deg margin)");

    // Elbow angle -81 + 90 - 6.83 = 2.2 deg: in front of the lower arm (cfx 0) but nearly
    // straight; J2 30 keeps the wrist centre well away from axis 1.
    const IkResult elbow = solve_tool0(m, forward_kinematics(g, deg({0, 30, -81, 0, 30, 0})), home);
    EXPECT_EQ(elbow.failure.kind, IkFailureKind::elbow_singularity);
    EXPECT_EQ(elbow.failure.axis, 3);
    EXPECT_EQ(elbow.failure.reason,
              "joint 3 at -81.0 deg is within the 5 deg elbow-singularity margin of -83.2 deg");

    // Upper arm straight up: wrist centre (-42, 0, 1100.1), 42 mm from axis 1.
    const IkResult shoulder =
        solve_tool0(m, forward_kinematics(g, deg({0, 0, -90, 0, 30, 0})), home);
    EXPECT_EQ(shoulder.failure.kind, IkFailureKind::shoulder_singularity);
    EXPECT_EQ(shoulder.failure.reason,
              "wrist centre 42.0 mm from the axis-1 line, within the 50 mm shoulder-singularity "
              "margin");

    // One pose, three branches: the default (front, elbow up, J5+) gives the joints it came from;
    // behind axis 1 with J1 -160 the arm must lean back: on cfx 4 J2 -103.8 is past its -100
    // stop, on cfx 6 (over the top, J3 -176.4) every joint fits.
    const Eigen::Isometry3d reachable = forward_kinematics(g, deg({20, 10, 10, 30, 60, -40}));
    const IkResult front = solve_tool0(m, reachable, home);
    ASSERT_TRUE(front.ok());
    EXPECT_NEAR(rad_to_deg(front.joints[1]), 10, 1e-9);
    JointSolverOptions behind;
    behind.cfx = 4;
    const IkResult back = solve_tool0(m, reachable, home, behind);
    EXPECT_EQ(back.failure.kind, IkFailureKind::joint_limit);
    EXPECT_EQ(back.failure.axis, 2);
    EXPECT_NEAR(back.failure.value, -103.78, 0.01);
    behind.cfx = 6;
    const IkResult over = solve_tool0(m, reachable, home, behind);
    ASSERT_TRUE(over.ok()) << over.failure.reason;
    EXPECT_NEAR(rad_to_deg(over.joints[0]), -160, 1e-9);
    EXPECT_EQ(over.conf, confdata(g, over.joints));
    expect_pose_near(forward_kinematics(g, over.joints), reachable);

    JointSolverOptions bad;
    bad.cfx = 8;
    EXPECT_THROW(solve_tool0(m, reachable, home, bad), std::invalid_argument);
}

// Tool pointing down (J5 90), turned about its own axis in 10 deg steps: J6 follows the turn
// past +-180 deg with no jump, and the wind-up stops at the +-360 deg limit less the margin.
TEST(Irb1200JointSolver, UnwrapsJointSixAcrossMoreThanATurn) {
    const RobotModel m = irb1200();
    const JointVector start = deg({0, 0, 0, 0, 90, 0});
    const Eigen::Isometry3d down = forward_kinematics(m.geometry, start);
    for (const double dir : {1.0, -1.0}) {
        std::vector<Eigen::Isometry3d> targets;
        for (int k = 0; k <= 80; ++k)
            targets.push_back(down * pose({0, 0, 0}, rot_z_deg(dir * 10 * k)));
        const PathSolution path = solve_path(m, TcpFrames{}, targets, start);
        ASSERT_EQ(path.points.size(), 36u);  // 0..350 deg; 360 is past 358
        for (std::size_t k = 0; k < path.points.size(); ++k) {
            const JointVector& q = path.points[k].joints;
            EXPECT_NEAR(rad_to_deg(q[5]), dir * 10.0 * static_cast<double>(k), 1e-9);
            for (int i = 0; i < 5; ++i) EXPECT_NEAR(q[i], start[i], 1e-9);
            EXPECT_EQ(path.points[k].conf.cf6, quadrant(q[5]));
        }
        EXPECT_EQ(path.failure.kind, IkFailureKind::joint_limit);
        EXPECT_EQ(path.failure.axis, 6);
        EXPECT_NEAR(path.failure.value, dir * 360, 1e-6);
    }
}

// A tilted nozzle 150 mm out from the flange, on a bed turned 90 deg about z at (400, -100, 50).
TEST(Irb1200JointSolver, PutsTheToolTcpAtABedPose) {
    const RobotModel m = irb1200();
    TcpFrames f;
    f.tool = pose({0, 20, 150},
                  Eigen::AngleAxisd(deg_to_rad(15), Eigen::Vector3d::UnitX()).toRotationMatrix());
    f.work_object = pose({400, -100, 50}, rot_z_deg(90));
    const Eigen::Isometry3d tcp =
        pose({50, 20, 10},
             Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix());
    expect_pose_near(tcp_in_work_object(f, tool0_for_tcp(f, tcp)), tcp);
    const IkResult r = solve_tcp(m, f, tcp, JointVector{});
    ASSERT_TRUE(r.ok()) << r.failure.reason;
    expect_pose_near(tcp_in_work_object(f, forward_kinematics(m.geometry, r.joints)), tcp);
    EXPECT_EQ(r.conf.cfx, 0);
}
