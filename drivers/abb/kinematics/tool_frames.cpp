#include "drivers/abb/kinematics/tool_frames.hpp"

namespace fibrecell::drivers::abb {

Eigen::Isometry3d tool0_for_tcp(const TcpFrames& frames,
                                const Eigen::Isometry3d& tcp_in_work_object) {
    // base->tool0 = base->bed * bed->TCP * (tool0->TCP)^-1
    return frames.work_object * tcp_in_work_object * frames.tool.inverse(Eigen::Isometry);
}

Eigen::Isometry3d tcp_in_work_object(const TcpFrames& frames,
                                     const Eigen::Isometry3d& tool0_in_base) {
    return frames.work_object.inverse(Eigen::Isometry) * tool0_in_base * frames.tool;
}

}  // namespace fibrecell::drivers::abb
