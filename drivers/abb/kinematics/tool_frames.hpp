#pragma once
// From "this tool's TCP at this pose on the bed" to the tool0 pose the arm must reach, and back.
// The frames are RAPID's: tooldata.tframe (flange -> TCP) and wobjdata (base -> bed, with the
// robot base as the world frame: uframe * oframe). Poses [mm].

#include <Eigen/Geometry>

namespace fibrecell::drivers::abb {

struct TcpFrames {
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();         // tool0 -> TCP (tframe)
    Eigen::Isometry3d work_object = Eigen::Isometry3d::Identity();  // base -> bed (wobj)
};

// tool0 in the base frame that puts the TCP at `tcp_in_work_object`.
Eigen::Isometry3d tool0_for_tcp(const TcpFrames& frames,
                                const Eigen::Isometry3d& tcp_in_work_object);

// The TCP in the work object when tool0 is at `tool0_in_base`.
Eigen::Isometry3d tcp_in_work_object(const TcpFrames& frames,
                                     const Eigen::Isometry3d& tool0_in_base);

}  // namespace fibrecell::drivers::abb
