#pragma once
// From a job's toolpaths to the robot's side of the plan directory: the print program (moves and
// events) and the RAPID chunk modules in DIR/rapid/, with the `robot` part of report.json. The
// offline `fibrecell plan` and the service plan jobs through this one path.

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "planner/job/job_spec.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <vector>

namespace fibrecell::daemon {

struct RobotPlan {
    drivers::abb::PrintProgram program;
    drivers::abb::RapidStats rapid;
    double seconds = 0;  // program + RAPID generation, wall clock
};

// layers: the job's toolpaths (bed frame). Writes `rapid_dir` (replacing it whole). Throws
// drivers::abb::PrintProgramError or RapidWriteError naming the layer, path and point of the first
// problem (an unreachable target, the idle nozzle too low, a fibre path shorter than the cutter).
RobotPlan plan_robot(const planner::JobSpec& job, const std::vector<planner::ToolpathLayer>& layers,
                     const drivers::abb::RobotCellConfig& robot,
                     const std::filesystem::path& rapid_dir);

// report["robot"] = {modules, lines, moves, events, barriers, head_switches, duration_s,
// print_length_m, travel_length_m}; report["timings_s"]["rapid"].
void add_robot_report(nlohmann::json& report, const RobotPlan& plan);

}  // namespace fibrecell::daemon
