#pragma once
// Values exchanged over Robot Web Services 1.0, shared by the client, the server and the
// controller backend. Enumerators are spelt as RWS spells the values on the wire.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::drivers::abb::rws {

// /rw/rapid/execution: ctrlexecstate.
enum class ExecutionState { running, stopped };

// /rw/panel/ctrlstate: ctrlstate.
enum class ControllerState {
    init,
    motoron,
    motoroff,
    guardstop,
    emergencystop,
    emergencystopreset,
    sysfail,
};

std::string_view to_string(ExecutionState s);
std::string_view to_string(ControllerState s);
std::optional<ExecutionState> parse_execution_state(std::string_view text);
std::optional<ControllerState> parse_controller_state(std::string_view text);

// The form fields of POST /rw/rapid/execution?action=start, with RWS's usual values.
struct StartOptions {
    std::string regain = "continue";     // continue | regain | clear | enter_consume
    std::string execmode = "continue";   // continue | stepin | stepover | stepout | ...
    std::string cycle = "once";          // once | forever | asis
    std::string condition = "none";      // none | callchain
    std::string stopatbp = "disabled";   // disabled | enabled
    std::string alltaskbytsp = "false";  // true | false
};

// GET /rw/rapid/execution.
struct ExecutionInfo {
    ExecutionState state = ExecutionState::stopped;
    std::string cycle = "once";  // once | forever | asis | oncedone
};

// One module of a task (GET /rw/rapid/modules?task=...): type "ProgMod" or "SysMod".
struct ModuleInfo {
    std::string name;
    std::string type = "ProgMod";
};

// One entry of a task's build log (GET /rw/rapid/tasks/{task}/program/builderror).
struct BuildError {
    std::string module;  // ModuleName
    std::size_t row = 0;
    std::size_t column = 0;
    std::string message;  // error
};

// "Print_0001 line 12: message" (column when known).
std::string format(const BuildError& e);

}  // namespace fibrecell::drivers::abb::rws
