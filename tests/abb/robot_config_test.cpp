// The `robot:` section of the cell YAML: defaults, the example files, strict keys and bounds,
// the head tilt geometry, and that the default bed lies comfortably inside the IRB 1200-7/0.7's
// reach for both nozzle tilts.
#include "drivers/abb/cell/robot_config.hpp"

#include "config/yaml_section.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "tests/support/project_paths.hpp"
#include "head_tilt.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace fibrecell;
using namespace fibrecell::drivers::abb;
using fibrecell::test::signed_tilt_deg;

namespace {

RobotCellConfig load_text(const std::string& yaml) {
    return load_robot_config(config::Section::load_text(yaml, "cell.yaml").section("robot"));
}

RobotCellConfig load_file(const std::string& name) {
    return load_robot_config(
        config::Section::load_file(fibrecell::test::test_data_path("abb/") + name)
            .section("robot"));
}

// Message of the ConfigError the YAML raises ("" when it loads).
std::string error_of(const std::string& yaml) {
    try {
        load_text(yaml);
    } catch (const config::ConfigError& e) {
        return e.what();
    }
    return "";
}

Eigen::Isometry3d tcp_pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = q.toRotationMatrix();
    t.translation() = p;
    return t;
}

// Signed angle [deg] from the bed's -z to the tool z axis, about `axis` (bed frame).
}  // namespace

TEST(RobotConfig, EmptySectionGivesTheSimulatedCell) {
    const RobotCellConfig c = load_text("robot: {}\n");
    EXPECT_EQ(c.variant, Irb1200Variant::irb1200_7_70);
    EXPECT_EQ(c.solver.cfx, 1);
    EXPECT_NEAR((c.bed.translation() - Eigen::Vector3d(380, -150, 100)).norm(), 0, 1e-12);
    EXPECT_TRUE(c.bed.linear().isIdentity(1e-12));
    EXPECT_EQ(c.head.tilt_deg, 15);
    EXPECT_EQ(c.head.idle_clearance_mm, 3);
    EXPECT_EQ(c.rapid.max_chunk_lines, 5000);
    EXPECT_EQ(c.signals.event, "goFcEvent");
    EXPECT_EQ(c.signals.all().size(), 8u);
    // An absent section is the same.
    const RobotCellConfig absent = load_text("name: x\n");
    EXPECT_EQ(absent.solver.cfx, c.solver.cfx);
    EXPECT_TRUE(absent.head.pla.tframe.isApprox(c.head.pla.tframe));
    // And the struct's own defaults match the loader's.
    const RobotCellConfig plain;
    EXPECT_TRUE(plain.bed.isApprox(c.bed));
    EXPECT_TRUE(plain.head.ccf.tframe.isApprox(c.head.ccf.tframe));
    EXPECT_EQ(plain.solver.cfx, c.solver.cfx);
    EXPECT_EQ(plain.motion.min_segment_mm, c.motion.min_segment_mm);
}

TEST(RobotConfig, ExampleFilesLoad) {
    const RobotCellConfig sim = load_file("robot-sim.yaml");
    const RobotCellConfig real = load_file("robot-irc5.yaml");
    EXPECT_TRUE(sim.bed.isApprox(real.bed));
    // rpy [0, 90, 0] and the quaternion [0.7071068, 0, 0.7071068, 0] are the same turn.
    EXPECT_TRUE(real.head.pla.tframe.linear().isApprox(real.head.ccf.tframe.linear(), 1e-6));
    EXPECT_TRUE(real.head.ccf.tframe.isApprox(sim.head.ccf.tframe, 1e-6));
    EXPECT_EQ(real.signals.running, "doFcRunning");
}

TEST(RobotConfig, ReadsEveryKey) {
    const RobotCellConfig c = load_text(R"(
robot:
  variant: "5/0.9"
  kinematics: {cfx: 0, limit_margin_deg: 3, wrist_margin_deg: 6, elbow_margin_deg: 7, shoulder_margin_mm: 60}
  bed: {position_mm: [400, -100, 50], quaternion: [0.7071068, 0, 0, 0.7071068]}
  head:
    tilt_axis: [0, 0, 2]
    tilt_deg: 12
    yaw_deg: 90
    idle_clearance_mm: 2
    pla: {position_mm: [90, -30, 55], rpy_deg: [0, 90, 0], mass_kg: 1.5, cog_mm: [40, 1, 50]}
    ccf: {position_mm: [90, 30, 55], mass_kg: 1.5, cog_mm: [40, 1, 50]}
  motion: {max_travel_speed_mm_s: 80, approach_speed_mm_s: 10, turn_speed_deg_s: 30, print_zone_mm: 0.5,
           travel_zone_mm: 2, safe_height_mm: 4, head_switch_height_mm: 25, chord_tolerance_mm: 0.05,
           min_segment_mm: 0.5, fine_allowance_s: 0.1}
  rapid: {max_chunk_lines: 3000, trigger_lag_s: 0.08, confl: true}
  signals: {event: goEv, barrier: goBar, release: giRel, pause: diP, abort: diA,
            heartbeat_in: diHb, heartbeat_out: doHb, running: doRun}
)");
    EXPECT_EQ(c.variant, Irb1200Variant::irb1200_5_90);
    EXPECT_EQ(c.solver.cfx, 0);
    EXPECT_EQ(c.solver.shoulder_margin_mm, 60);
    EXPECT_NEAR((c.bed.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0,
                1e-6);
    EXPECT_NEAR((c.head.tilt_axis - Eigen::Vector3d::UnitZ()).norm(), 0, 1e-12);  // normalised
    EXPECT_EQ(c.head.tilt_deg, 12);
    EXPECT_EQ(c.head.yaw_deg, 90);
    EXPECT_EQ(c.head.pla.mass_kg, 1.5);
    // An orientation left out keeps the default nozzle orientation.
    EXPECT_TRUE(c.head.ccf.tframe.linear().isApprox(HeadConfig{}.ccf.tframe.linear()));
    EXPECT_NEAR((c.head.ccf.tframe.translation() - Eigen::Vector3d(90, 30, 55)).norm(), 0, 1e-12);
    EXPECT_EQ(c.motion.max_travel_speed_mm_s, 80);
    EXPECT_EQ(c.motion.head_switch_height_mm, 25);
    EXPECT_EQ(c.motion.min_segment_mm, 0.5);
    EXPECT_EQ(c.rapid.max_chunk_lines, 3000);
    EXPECT_TRUE(c.rapid.confl);
    EXPECT_EQ(c.signals.heartbeat_out, "doHb");
}

TEST(RobotConfig, RejectsBadValuesNamingTheKey) {
    EXPECT_NE(error_of("robot: {colour: red}\n").find("robot.colour: unknown key"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {head: {pla: {size_mm: 3}}}\n").find("robot.head.pla.size_mm"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {variant: \"6/0.8\"}\n").find("robot.variant"), std::string::npos);
    EXPECT_NE(error_of("robot: {kinematics: {cfx: 8}}\n").find("robot.kinematics.cfx"),
              std::string::npos);
    EXPECT_NE(
        error_of("robot: {rapid: {max_chunk_lines: 10}}\n").find("robot.rapid.max_chunk_lines"),
        std::string::npos);
    EXPECT_NE(error_of("robot: {motion: {max_travel_speed_mm_s: 0}}\n")
                  .find("robot.motion.max_travel_speed_mm_s"),
              std::string::npos);
    // The travel speed moved to the job; an old cell file says where.
    EXPECT_NE(error_of("robot: {motion: {travel_speed_mm_s: 100}}\n")
                  .find("robot.motion.travel_speed_mm_s: the travel speed is the job's"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {bed: {rpy_deg: [0, 0, 0], quaternion: [1, 0, 0, 0]}}\n")
                  .find("either rpy_deg or quaternion"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {bed: {quaternion: [1, 1, 0, 0]}}\n").find("unit length"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {bed: {position_mm: [1, 2]}}\n").find("robot.bed.position_mm"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {signals: {event: 2goEvent}}\n").find("robot.signals.event"),
              std::string::npos);
    EXPECT_NE(error_of("robot: {signals: {abort: MODULE}}\n").find("reserved"), std::string::npos);
    EXPECT_NE(error_of("robot: {head: {tilt_axis: [0, 0, 0]}}\n").find("robot.head.tilt_axis"),
              std::string::npos);
    // Nozzles along tool0 +x cannot be tilted about tool0 x.
    EXPECT_NE(error_of("robot: {head: {tilt_axis: [1, 0, 0]}}\n").find("perpendicular"),
              std::string::npos);
    // 4 mm apart, a 15 deg tilt lifts the idle tip by 1.04 mm: under the 3 mm clearance.
    EXPECT_NE(error_of("robot: {head: {pla: {position_mm: [95, -2, 60]}, "
                       "ccf: {position_mm: [95, 2, 60]}}}\n")
                  .find("less than idle_clearance_mm"),
              std::string::npos);
}

TEST(RobotConfig, TiltLiftsTheIdleNozzle) {
    const HeadConfig h;
    // PLA at tool0 y = -25, CCF at +25, both along tool0 +x; the tilt axis (tool0 z) lies along
    // bed +x, tool0 y along bed +y. Turning by +15 deg about +x raises the +y side: CCF.
    EXPECT_DOUBLE_EQ(nozzle_tilt_deg(h, Nozzle::pla), 15);
    EXPECT_DOUBLE_EQ(nozzle_tilt_deg(h, Nozzle::ccf), -15);
    const double lift = 50 * std::sin(15 * std::numbers::pi / 180);  // 12.94 mm
    EXPECT_NEAR(idle_lift_mm(h, Nozzle::pla), lift, 1e-9);
    EXPECT_NEAR(idle_lift_mm(h, Nozzle::ccf), lift, 1e-9);

    for (const Nozzle n : {Nozzle::pla, Nozzle::ccf}) {
        const Eigen::Quaterniond q = print_orientation(h, n);
        EXPECT_NEAR(signed_tilt_deg(q, Eigen::Vector3d::UnitX()), n == Nozzle::pla ? 15 : -15,
                    1e-9);
        // The idle tip, computed through the flange by hand.
        const Eigen::Isometry3d tcp = tcp_pose(Eigen::Vector3d(10, 20, 0.8), q);
        const Eigen::Isometry3d flange = tcp * h.nozzle(n).tframe.inverse();
        const Eigen::Vector3d idle = flange * h.nozzle(other(n)).tframe.translation();
        EXPECT_NEAR((idle_tip_position(h, n, tcp) - idle).norm(), 0, 1e-9);
        EXPECT_NEAR(idle.z() - 0.8, lift, 1e-9);
    }
}

TEST(RobotConfig, TiltFollowsYawAndMirroredNozzles) {
    HeadConfig h;
    h.yaw_deg = 90;                                 // tilt axis along bed +y
    h.pla.tframe = HeadConfig::default_tframe(25);  // PLA on the other side now
    h.ccf.tframe = HeadConfig::default_tframe(-25);
    EXPECT_DOUBLE_EQ(nozzle_tilt_deg(h, Nozzle::pla), -15);
    EXPECT_DOUBLE_EQ(nozzle_tilt_deg(h, Nozzle::ccf), 15);
    const Eigen::Quaterniond q = print_orientation(h, Nozzle::pla);
    EXPECT_NEAR(signed_tilt_deg(q, Eigen::Vector3d::UnitY()), -15, 1e-9);
    EXPECT_GT(idle_lift_mm(h, Nozzle::pla), 12.9);
}

TEST(RobotConfig, RpyIsFixedAxesXyz) {
    const Eigen::Quaterniond q = rpy_deg_to_quaternion(90, 0, 90);
    // x first: y -> z; then z: x -> y. So y -> z -> z, x -> x -> y.
    EXPECT_NEAR((q * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 0, 1e-12);
    EXPECT_NEAR((q * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0, 1e-12);
}

// The default bed and head: the four corners and the centre of the 300 x 300 mm bed area at z 0
// and 30 mm (and the 50 mm ceiling of the brief) reachable on the configured branch with both
// nozzle tilts, with room to spare inside the solver's margins.
TEST(RobotConfig, DefaultBedIsReachableWithBothTilts) {
    const RobotCellConfig c;
    const RobotModel robot = c.model();
    JointSolverOptions generous = c.solver;  // margins well beyond the defaults
    generous.limit_margin_deg = 10;
    generous.wrist_margin_deg = 30;
    generous.elbow_margin_deg = 20;
    generous.shoulder_margin_mm = 150;
    const double xy[5][2] = {{0, 0}, {300, 0}, {0, 300}, {300, 300}, {150, 150}};
    for (const Nozzle n : {Nozzle::pla, Nozzle::ccf})
        for (const double z : {0.0, 30.0, 50.0})
            for (const auto& p : xy) {
                const Eigen::Isometry3d target =
                    tcp_pose(Eigen::Vector3d(p[0], p[1], z), print_orientation(c.head, n));
                const IkResult r = solve_tcp(robot, c.frames(n), target, JointVector{}, generous);
                EXPECT_TRUE(r.ok()) << to_string(n) << " at (" << p[0] << ", " << p[1] << ", " << z
                                    << "): " << r.failure.reason;
                EXPECT_EQ(r.conf.cfx, c.solver.cfx);
                // FK of the solution puts the nozzle tip back on the bed point.
                const Eigen::Isometry3d tip = c.bed.inverse() *
                                              forward_kinematics(robot.geometry, r.joints) *
                                              c.head.nozzle(n).tframe;
                EXPECT_NEAR((tip.translation() - Eigen::Vector3d(p[0], p[1], z)).norm(), 0, 1e-6);
            }
}

TEST(RobotConfig, DefaultBedAlsoFitsTheLongArm) {
    RobotCellConfig c;
    c.variant = Irb1200Variant::irb1200_5_90;
    for (const Nozzle n : {Nozzle::pla, Nozzle::ccf})
        for (const double x : {0.0, 300.0})
            for (const double y : {0.0, 300.0}) {
                const Eigen::Isometry3d target =
                    tcp_pose(Eigen::Vector3d(x, y, 30), print_orientation(c.head, n));
                EXPECT_TRUE(
                    solve_tcp(c.model(), c.frames(n), target, JointVector{}, c.solver).ok());
            }
}
