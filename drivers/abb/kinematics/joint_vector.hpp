#pragma once
// Joint vectors of the six-axis arm and the angle helpers the kinematics share.

#include <array>
#include <cmath>
#include <numbers>

namespace fibrecell::drivers::abb {

// Axes 1..6 in the controller's convention (what a RAPID jointtarget shows, here in radians).
using JointVector = std::array<double, 6>;

constexpr double deg_to_rad(double deg) {
    return deg * (std::numbers::pi / 180);
}
constexpr double rad_to_deg(double rad) {
    return rad * (180 / std::numbers::pi);
}

// a + 2*pi*k in (-pi, pi].
inline double wrap_to_pi(double a) {
    const double r = std::remainder(a, 2 * std::numbers::pi);  // [-pi, pi]
    return r <= -std::numbers::pi ? r + 2 * std::numbers::pi : r;
}

// The 2*pi-equivalent of `a` nearest to `reference`.
inline double nearest_turn(double a, double reference) {
    return reference + wrap_to_pi(a - reference);
}

}  // namespace fibrecell::drivers::abb
