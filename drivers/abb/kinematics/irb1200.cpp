#include "drivers/abb/kinematics/irb1200.hpp"

#include <numbers>

namespace fibrecell::drivers::abb {
namespace {

JointVector degrees(const JointVector& deg) {
    JointVector rad;
    for (int i = 0; i < 6; ++i) rad[i] = deg_to_rad(deg[i]);
    return rad;
}

}  // namespace

RobotModel irb1200(Irb1200Variant variant) {
    const bool long_arm = variant == Irb1200Variant::irb1200_5_90;
    RobotModel m;
    m.name = long_arm ? "IRB 1200-5/0.9" : "IRB 1200-7/0.7";
    // MoveIt opw_kinematics configs of ROS-I abb_irb1200_*_moveit_config, in mm.
    m.geometry.a1 = 0;
    m.geometry.a2 = -42;
    m.geometry.b = 0;
    m.geometry.c1 = 399.1;
    m.geometry.c2 = long_arm ? 448 : 350;
    m.geometry.c3 = long_arm ? 451 : 351;
    m.geometry.c4 = 82;
    m.geometry.offsets = {0, 0, -std::numbers::pi / 2, 0, 0, 0};
    // Datasheet ROB0275EN_A ranges; axis 6 at +-360 deg, the range without the extended option.
    m.limits.lower_rad = degrees({-170, -100, -200, -270, -130, -360});
    m.limits.upper_rad = degrees({170, long_arm ? 130.0 : 135.0, 70, 270, 130, 360});
    m.limits.max_speed_rad_s = degrees({288, 240, 300, 400, 405, 600});
    return m;
}

std::optional<Irb1200Variant> parse_irb1200_variant(std::string_view text) {
    for (const auto v : {Irb1200Variant::irb1200_7_70, Irb1200Variant::irb1200_5_90}) {
        const bool long_arm = v == Irb1200Variant::irb1200_5_90;
        if (text == irb1200(v).name || text == (long_arm ? "5/0.9" : "7/0.7") ||
            text == (long_arm ? "irb1200_5_90" : "irb1200_7_70"))
            return v;
    }
    return std::nullopt;
}

}  // namespace fibrecell::drivers::abb
