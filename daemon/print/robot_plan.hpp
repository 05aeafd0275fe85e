#pragma once
// From a job's toolpaths to the robot's side of its plan: the print program (moves and events)
// and the RAPID chunk modules, with the `robot` part of report.json. The offline `fibrecell plan`
// and the service plan jobs through this one path; plan_files.hpp writes the result.

#include "daemon/print/print_settings.hpp"
#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fibrecell::daemon::print {

struct RobotPlan {
    drivers::abb::PrintProgram program;
    drivers::abb::RapidOutput rapid;  // the chunk modules and the joints of every move
    double seconds = 0;               // program + RAPID generation, wall clock
};

// The plan's toolpaths as the robot driver takes them: a layer's head is its nozzle.
std::vector<drivers::abb::RobotLayer> robot_layers(const std::vector<planner::ToolpathLayer>& layers);

// layers: the job's toolpaths (bed frame). Throws drivers::abb::PrintProgramError or
// RapidWriteError naming the layer, path and point of the first problem (an unreachable target,
// the idle nozzle too low, a fibre path shorter than the cutter).
RobotPlan plan_robot(const std::vector<planner::ToolpathLayer>& layers,
                     const drivers::abb::RobotCellConfig& robot, const PrintSettings& settings,
                     const std::string& job_name);

// report["robot"] = {modules, lines, moves, events, barriers, head_switches, duration_s,
// print_length_m, travel_length_m}; report["timings_s"]["rapid"].
void add_robot_report(nlohmann::json& report, const RobotPlan& plan);

}  // namespace fibrecell::daemon::print
