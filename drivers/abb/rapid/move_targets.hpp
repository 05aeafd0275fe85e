#pragma once
// Every target a motion instruction moves to, with its line and the tool and work object it is
// used with: the input of the checks that need kinematics (confdata against the IRB 1200 IK,
// joint limits with margin), which live with the kinematics, not here.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "drivers/abb/rapid/program.hpp"
#include "drivers/abb/rapid/robot_data.hpp"

namespace fibrecell::drivers::abb::rapid {

struct MoveTarget {
    std::string routine;
    std::string instruction;    // "MoveL", "TriggL", "MoveAbsJ", ... (canonical spelling)
    std::size_t line = 0;       // of the motion instruction
    bool circle_point = false;  // MoveC's first (via) point
    // The target's name when passed by name ("p10"), with the line of its declaration; empty and
    // 0 for an inline literal or an expression such as Offs(p10, 0, 0, 5).
    std::string target_name;
    std::size_t declared_line = 0;
    // The value when the reader can evaluate it from literals and initial values (a VAR changed
    // at run time is seen with its initial value). jointtarget for MoveAbsJ, robtarget otherwise.
    std::optional<Robtarget> robtarget;
    std::optional<JointTarget> jointtarget;
    std::string tool;                   // name as written; "" when the tool is an expression
    std::string wobj = "wobj0";         // \WObj name; wobj0 when absent
    std::optional<ToolData> tool_data;  // resolved from module data or predefined tool0
    std::optional<WobjData> wobj_data;
};

// In routine order, then source order.
std::vector<MoveTarget> move_targets(const Module& module);

}  // namespace fibrecell::drivers::abb::rapid
