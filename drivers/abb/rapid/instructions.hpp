#pragma once
// The built-in RAPID instructions the reader knows: their positional parameters (with the type the
// validator checks where a declared name or an aggregate is passed) and their optional arguments
// and switches. Syntax from the RAPID reference as summarised in docs/rapid-subset.md
// ("Statements", "Position events").

#include <cstddef>
#include <span>
#include <string_view>

namespace fibrecell::drivers::abb::rapid {

struct OptionalParam {
    std::string_view name;  // "WObj", "T2", "Start"
    std::string_view type;  // "" for a switch (\Start), else the value's type ("any" = unchecked)
};

// What a motion instruction's positional arguments mean, for the move-target listing.
struct MoveRoles {
    int target = -1;  // robtarget / jointtarget argument index
    int via = -1;     // MoveC's circle point
    int speed = -1;
    int zone = -1;
    int tool = -1;
    int trigger = -1;  // TriggL/TriggJ: first triggdata
};

struct InstructionInfo {
    std::string_view name;                     // canonical spelling: "MoveL"
    std::span<const std::string_view> params;  // positional parameter types, in order
    std::span<const OptionalParam> optionals;
    MoveRoles move;                // all -1 for non-motion instructions
    bool sets_up_trigger = false;  // TriggIO, TriggEquip, TriggInt, TriggSpeed
};

// nullptr when `name` is not a built-in instruction of the subset. Case-insensitive.
const InstructionInfo* find_instruction(std::string_view name);

bool is_builtin_instruction(std::string_view name);

// MoveL, MoveJ, MoveC, MoveAbsJ, MoveLDO, TriggL, TriggJ.
inline bool is_motion(const InstructionInfo& info) {
    return info.move.target >= 0;
}

// \T2 ... \T8 of TriggL/TriggJ.
bool is_extra_trigger(std::string_view optional_name);

}  // namespace fibrecell::drivers::abb::rapid
