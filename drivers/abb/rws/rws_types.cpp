#include "drivers/abb/rws/rws_types.hpp"

#include <array>
#include <utility>

namespace fibrecell::drivers::abb::rws {

namespace {

constexpr std::array<std::pair<ControllerState, std::string_view>, 7> controller_states{{
    {ControllerState::init, "init"},
    {ControllerState::motoron, "motoron"},
    {ControllerState::motoroff, "motoroff"},
    {ControllerState::guardstop, "guardstop"},
    {ControllerState::emergencystop, "emergencystop"},
    {ControllerState::emergencystopreset, "emergencystopreset"},
    {ControllerState::sysfail, "sysfail"},
}};

}  // namespace

std::string_view to_string(ExecutionState s) {
    return s == ExecutionState::running ? "running" : "stopped";
}

std::string_view to_string(ControllerState s) {
    for (const auto& [state, name] : controller_states)
        if (state == s) return name;
    return "unknown";
}

std::optional<ExecutionState> parse_execution_state(std::string_view text) {
    if (text == "running") return ExecutionState::running;
    if (text == "stopped") return ExecutionState::stopped;
    return std::nullopt;
}

std::optional<ControllerState> parse_controller_state(std::string_view text) {
    for (const auto& [state, name] : controller_states)
        if (name == text) return state;
    return std::nullopt;
}

std::string format(const BuildError& e) {
    std::string out = e.module + " line " + std::to_string(e.row);
    if (e.column > 0) out += " column " + std::to_string(e.column);
    return out + ": " + e.message;
}

}  // namespace fibrecell::drivers::abb::rws
