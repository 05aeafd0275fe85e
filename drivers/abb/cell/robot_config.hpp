#pragma once
// The `robot:` section of the cell YAML: the IRB 1200, where the bed is, the dual head on the
// flange (two nozzles, the +-15 deg tilt that lifts the idle one), motion parameters for the print
// program and the RAPID chunks, and the I/O signal names. Units are in the key names; every key
// has a default, so an empty section describes the simulated cell (docs/robot-program.md).
//
// Frames (docs/kinematics.md): base = robot base; bed = the work object, origin at a corner of the
// print area, z up; flange = tool0 (z out of the flange). A nozzle's tool frame has its origin at
// the nozzle tip and z along the nozzle (pointing out of the tip).

#include "config/yaml_section.hpp"
#include "drivers/abb/kinematics/irb1200.hpp"
#include "drivers/abb/kinematics/joint_solver.hpp"
#include "drivers/abb/kinematics/tool_frames.hpp"

#include <Eigen/Geometry>

#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::abb {

enum class Nozzle { pla, ccf };

std::string_view to_string(Nozzle n);
inline Nozzle other(Nozzle n) {
    return n == Nozzle::pla ? Nozzle::ccf : Nozzle::pla;
}

struct NozzleConfig {
    // tool0 -> nozzle tip (RAPID tooldata.tframe) [mm]; z along the nozzle, out of the tip.
    Eigen::Isometry3d tframe = Eigen::Isometry3d::Identity();
    double mass_kg = 1.2;                                 // tooldata.tload: the whole head
    Eigen::Vector3d cog_mm = Eigen::Vector3d(50, 0, 60);  // in the flange frame
};

struct HeadConfig {
    // Defaults: the head hangs from a horizontal flange. Both nozzles point along tool0 +x (down
    // when the flange faces away from the robot), 95 mm below and 60 mm in front of the flange
    // centre, 50 mm apart across the tilt axis: a 15 deg tilt lifts the idle tip by 12.9 mm.
    NozzleConfig pla = {.tframe = default_tframe(-25)};
    NozzleConfig ccf = {.tframe = default_tframe(25)};
    Eigen::Vector3d tilt_axis = Eigen::Vector3d::UnitZ();  // flange frame, unit; joint 6 axis
    double tilt_deg = 15;  // magnitude; the sign per nozzle is the one that lifts the idle nozzle
    // Direction of the tilt axis in the bed plane, deg from bed +x (0: the flange faces bed +x).
    double yaw_deg = 0;
    double idle_clearance_mm = 3;  // idle nozzle tip above the part's current top, at least

    const NozzleConfig& nozzle(Nozzle n) const { return n == Nozzle::pla ? pla : ccf; }
    static Eigen::Isometry3d default_tframe(double y_mm);
};

struct RobotMotionConfig {
    double max_travel_speed_mm_s = 250; // the highest lift/travel speed a job may ask for
    double approach_speed_mm_s = 20;    // the last descent onto a path start
    double turn_speed_deg_s = 60;       // reorientation at a head switch (speeddata v_ori)
    double print_zone_mm = 0.3;         // fly-by zone between print moves
    double travel_zone_mm = 5;          // fly-by zone between travel moves
    double safe_height_mm = 5;          // travel this far above the part's current top
    double head_switch_height_mm = 20;  // turn the head this far above the part's current top
    double chord_tolerance_mm = 0.02;   // merged points stay this close to the toolpath
    double min_segment_mm = 0.3;        // shorter print segments are merged (controller load)
    double fine_allowance_s = 0.2;      // duration estimate: extra time per stop point
};

struct RapidConfig {
    int max_chunk_lines = 5000;   // per chunk module (docs/robot-program.md, "The RAPID chunks")
    double trigger_lag_s = 0.05;  // TriggEquip EquipLag for events that drive the extruder
    bool confl = false;           // ConfL \On (check cf1/cf4/cf6 on linear moves) or \Off
};

// Controller I/O names (EIO configuration), shared with the resident main module FcMain.
struct RobotSignals {
    std::string event = "goFcEvent";      // group output, 16 bits: event sequence number
    std::string barrier = "goFcBarrier";  // group output: barrier the robot waits at
    std::string release = "giFcRelease";  // group input: barrier released by the service
    std::string pause = "diFcPause";
    std::string abort = "diFcAbort";
    std::string heartbeat_in = "diFcHeartbeat";
    std::string heartbeat_out = "doFcHeartbeat";
    std::string running = "doFcRunning";

    std::vector<std::string> all() const;
};

struct RobotCellConfig {
    Irb1200Variant variant = Irb1200Variant::irb1200_7_70;
    // base -> bed (RAPID wobjdata uframe; oframe identity) [mm]. The default puts the 300 x 300 mm
    // bed area in front of the robot, 180 mm below the base plate.
    Eigen::Isometry3d bed = default_bed();
    HeadConfig head;
    // cfx branch for the whole print and the solver margins (docs/kinematics.md). cfx 1 (front,
    // elbow up, J5 negative) is the branch of the default head: flange level, wrist bent up.
    JointSolverOptions solver = {.cfx = 1};
    RobotMotionConfig motion;
    RapidConfig rapid;
    RobotSignals signals;

    RobotModel model() const { return irb1200(variant); }
    // tool = the nozzle's tframe, work object = bed.
    TcpFrames frames(Nozzle n) const;
    static Eigen::Isometry3d default_bed();
};

// The signed tilt [deg] of the head while nozzle `n` prints: +-tilt_deg about the tilt axis, the
// sign that puts the idle nozzle's tip higher.
double nozzle_tilt_deg(const HeadConfig& head, Nozzle n);

// Orientation of nozzle `n`'s tool frame in the bed frame while it prints: untilted, its z is the
// bed's -z and the tilt axis lies along the bed direction yaw_deg; then turned by
// nozzle_tilt_deg about the tilt axis.
Eigen::Quaterniond print_orientation(const HeadConfig& head, Nozzle n);

// Pose of the other nozzle's tip (bed frame) when nozzle `active` has its TCP at `tcp_in_bed`.
Eigen::Vector3d idle_tip_position(const HeadConfig& head, Nozzle active,
                                  const Eigen::Isometry3d& tcp_in_bed);

// Height of the idle tip above the active one while printing with nozzle `n` [mm].
double idle_lift_mm(const HeadConfig& head, Nozzle n);

// Rotation from roll-pitch-yaw [deg] about fixed x, then y, then z (URDF): Rz * Ry * Rx.
Eigen::Quaterniond rpy_deg_to_quaternion(double roll_deg, double pitch_deg, double yaw_deg);

// Reads and checks the section (bounds, unknown keys, head geometry); throws config::ConfigError
// naming the key.
RobotCellConfig load_robot_config(config::Section section);

}  // namespace fibrecell::drivers::abb
