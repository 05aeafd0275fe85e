#pragma once
// Typed views of the RAPID motion data (docs/rapid-subset.md, "Records") for code that computes
// with them: the kinematics checks, the simulated controller, the writer's tests. Quaternions are
// written [q1,q2,q3,q4] = (w,x,y,z) in RAPID and are kept as read (not normalised): the validator
// checks the norm, the consumer decides.

#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "drivers/abb/rapid/value.hpp"

namespace fibrecell::drivers::abb::rapid {

// Axis quadrants of the intended IK solution: cf1/cf4/cf6 = floor(q/90°), cfx = the arm case.
struct ConfData {
    int cf1 = 0;
    int cf4 = 0;
    int cf6 = 0;
    int cfx = 0;
};

struct Pose {
    Eigen::Vector3d trans_mm = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rot = Eigen::Quaterniond::Identity();
};

// 9E9 marks an unused external axis.
inline constexpr double unused_extax = 9e9;

struct Robtarget {
    Eigen::Vector3d trans_mm = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rot = Eigen::Quaterniond::Identity();
    ConfData conf;
    std::array<double, 6> extax{unused_extax, unused_extax, unused_extax,
                                unused_extax, unused_extax, unused_extax};
};

struct JointTarget {
    std::array<double, 6> robax_deg{};
    std::array<double, 6> extax{unused_extax, unused_extax, unused_extax,
                                unused_extax, unused_extax, unused_extax};
};

struct LoadData {
    double mass_kg = 0;
    Eigen::Vector3d cog_mm = Eigen::Vector3d::Zero();
    Eigen::Quaterniond aom = Eigen::Quaterniond::Identity();  // axes of moment
    Eigen::Vector3d inertia_kgm2 = Eigen::Vector3d::Zero();   // ix, iy, iz
};

struct ToolData {
    bool robhold = true;  // TRUE: the robot holds the tool
    Pose tframe;          // TCP in the flange frame
    LoadData tload;
};

struct WobjData {
    bool robhold = false;
    bool ufprog = true;
    std::string ufmec;
    Pose uframe;  // user frame in world
    Pose oframe;  // object frame in the user frame
};

struct SpeedData {
    double v_tcp_mm_s = 0;
    double v_ori_deg_s = 0;
    double v_leax_mm_s = 0;
    double v_reax_deg_s = 0;
};

struct ZoneData {
    bool finep = false;  // TRUE: stop point (fine)
    double pzone_tcp_mm = 0;
    double pzone_ori_mm = 0;
    double pzone_eax_mm = 0;
    double zone_ori_deg = 0;
    double zone_leax_mm = 0;
    double zone_reax_deg = 0;
};

// From a value of the matching shape (typed or an untyped aggregate); nothing on a mismatch.
std::optional<Pose> to_pose(const Value& v);
std::optional<Robtarget> to_robtarget(const Value& v);
std::optional<JointTarget> to_jointtarget(const Value& v);
std::optional<LoadData> to_loaddata(const Value& v);
std::optional<ToolData> to_tooldata(const Value& v);
std::optional<WobjData> to_wobjdata(const Value& v);
std::optional<SpeedData> to_speeddata(const Value& v);
std::optional<ZoneData> to_zonedata(const Value& v);

// Typed values back to RAPID values (records named, ready for component access).
Value to_value(const Pose& p);
Value to_value(const Robtarget& t);
Value to_value(const JointTarget& t);
Value to_value(const LoadData& l);
Value to_value(const ToolData& t);
Value to_value(const WobjData& w);
Value to_value(const SpeedData& s);
Value to_value(const ZoneData& z);

}  // namespace fibrecell::drivers::abb::rapid
