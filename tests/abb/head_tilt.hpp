#pragma once
// The head's tilt as the robot tests measure it from a tool orientation, independently of how the
// program or the robot config computed it.

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace fibrecell::test {

// The angle [deg] between the tool's z axis and straight down, signed by the rotation about
// `axis` (bed frame) that takes down onto it.
inline double signed_tilt_deg(const Eigen::Quaterniond& q,
                              const Eigen::Vector3d& axis = Eigen::Vector3d::UnitX()) {
    const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d tz = q.normalized() * Eigen::Vector3d::UnitZ();
    return std::atan2(axis.dot(down.cross(tz)), down.dot(tz)) * 180 / std::numbers::pi;
}

}  // namespace fibrecell::test
