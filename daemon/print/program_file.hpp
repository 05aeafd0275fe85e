#pragma once
// program.json of the plan directory: the print program exactly as planning made it (every move
// with the joints its RAPID target was written from, every event), so that the print and a
// re-entry after an interruption work from the plan, never from the toolpaths again
// (docs/jobs.md, "The plan is the print").
//
//   {"format": "fibrecell.program/1",
//    "move_columns": ["role", "nozzle", "joint", "x_mm", ...], "moves": [["travel", "pla", 0, ...], ...],
//    "event_columns": ["sequence", "kind", ...], "events": [[1, "head_switch", ...], ...],
//    "stats": {...}}
//
// Numbers are written in their shortest form that reads back to the same double.

#include "drivers/abb/kinematics/joint_vector.hpp"
#include "drivers/abb/program/print_program.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::daemon::print {

inline constexpr std::string_view program_format = "fibrecell.program/1";

struct ProgramFile {
    drivers::abb::PrintProgram program;
    std::vector<drivers::abb::JointVector> joints;  // per move [rad]
};

std::string program_json_text(const drivers::abb::PrintProgram& program,
                              const std::vector<drivers::abb::JointVector>& joints);

// Throws std::invalid_argument naming `origin` and what is wrong (row and column).
ProgramFile parse_program_json(std::string_view text, const std::string& origin);

}  // namespace fibrecell::daemon::print
