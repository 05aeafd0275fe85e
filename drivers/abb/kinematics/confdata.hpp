#pragma once
// ABB confdata [cf1, cf4, cf6, cfx] of a joint vector (docs/kinematics.md, "confdata"): the
// quadrants of axes 1, 4 and 6, and cfx, which of the eight arm configurations the joints are in.

#include "drivers/abb/kinematics/opw_kinematics.hpp"

#include <string>

namespace fibrecell::drivers::abb {

struct ConfData {
    int cf1 = 0;  // quadrant of axis 1
    int cf4 = 0;  // quadrant of axis 4
    int cf6 = 0;  // quadrant of axis 6
    int cfx =
        0;  // 0..7: wrist centre behind axis 1 (+4), behind the lower arm (+2), axis 5 < 0 (+1)
    bool operator==(const ConfData&) const = default;
};

// floor(angle / 90 deg): 0 for [0, 90) deg, -1 for [-90, 0), 3 for [270, 360). Angles within
// 1e-9 rad below a multiple of 90 deg count as on it, so that 90 deg converted to radians is 1.
int quadrant(double angle_rad);

// cfx is the OPW branch (the bit order is the same), from the geometry of the joints.
ConfData confdata(const OpwParameters& p, const JointVector& q);

// RAPID literal: "[0,-1,2,0]".
std::string to_string(const ConfData& c);

}  // namespace fibrecell::drivers::abb
