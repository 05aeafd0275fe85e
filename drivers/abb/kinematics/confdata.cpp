#include "drivers/abb/kinematics/confdata.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace fibrecell::drivers::abb {

int quadrant(double angle_rad) {
    return static_cast<int>(std::floor((angle_rad + 1e-9) / (std::numbers::pi / 2)));
}

ConfData confdata(const OpwParameters& p, const JointVector& q) {
    return {quadrant(q[0]), quadrant(q[3]), quadrant(q[5]), branch_of(p, q)};
}

std::string to_string(const ConfData& c) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "[%d,%d,%d,%d]", c.cf1, c.cf4, c.cf6, c.cfx);
    return buf;
}

}  // namespace fibrecell::drivers::abb
