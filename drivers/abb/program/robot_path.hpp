#pragma once
// What the robot is given to lay: per layer, in print order, the paths one nozzle prints, in the
// bed frame [mm]. The robot driver's own type, so that it depends on no planner: the plan's
// toolpaths become these in daemon/print (robot_plan.hpp, robot_layers()).

#include "drivers/abb/cell/robot_config.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::drivers::abb {

struct RobotPath {
    bool closed = false;                  // the last point joins the first
    std::vector<Eigen::Vector2d> points;  // in print order [mm]
};

struct RobotLayer {
    int index = 0;  // 0-based, in print order: the layer the program's moves and events name
    double z = 0;   // nozzle-tip height while the layer prints [mm]
    // The nozzle of every path: a CCF layer's paths are fibre paths (threading barrier, cut,
    // path end), a PLA layer's are extruded.
    Nozzle nozzle = Nozzle::pla;
    std::vector<RobotPath> paths;
};

}  // namespace fibrecell::drivers::abb
