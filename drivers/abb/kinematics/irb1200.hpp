#pragma once
// ABB IRB 1200 (docs/kinematics.md, "Parameters" and "Sources"): the OPW geometry of its two
// variants, the datasheet joint ranges and speeds. The controller's axis 3 is the model's
// minus 90 deg (upper arm level at 0).

#include "drivers/abb/kinematics/opw_kinematics.hpp"

#include <optional>
#include <string_view>

namespace fibrecell::drivers::abb {

enum class Irb1200Variant {
    irb1200_7_70,  // IRB 1200-7/0.7: 7 kg, 703.5 mm wrist reach (ROS-I irb1200_7_70)
    irb1200_5_90,  // IRB 1200-5/0.9: 5 kg, 901.0 mm wrist reach (ROS-I irb1200_5_90)
};

struct JointLimits {
    JointVector lower_rad{};
    JointVector upper_rad{};
    JointVector max_speed_rad_s{};
};

// What the solver needs to know about an arm.
struct RobotModel {
    std::string_view name;  // "IRB 1200-7/0.7"
    OpwParameters geometry;
    JointLimits limits;
};

RobotModel irb1200(Irb1200Variant variant = Irb1200Variant::irb1200_7_70);

// "IRB 1200-7/0.7", "7/0.7" or "irb1200_7_70" (and the 5/0.9 spellings); nothing otherwise.
std::optional<Irb1200Variant> parse_irb1200_variant(std::string_view text);

}  // namespace fibrecell::drivers::abb
