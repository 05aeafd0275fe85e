#pragma once
// Lifecycle of a device link (extruder board, robot controller), after ros2_control's hardware
// lifecycle: the framework owns the state and moves a device between states; drivers implement
// the hooks. Written down as a table so that tests can walk every transition.

#include <optional>
#include <string_view>

namespace fibrecell::drivers {

enum class DeviceState {
    unconfigured,  // created, settings not applied -> configuring
    inactive,      // configured, link closed -> activating, unconfigured
    active,        // link open and healthy -> inactive, error
    error,         // a fault was seen; held until an operator clears it -> unconfigured
};

enum class DeviceEvent { configure, activate, deactivate, fault, clear, reset };

std::string_view to_string(DeviceState s);
std::string_view to_string(DeviceEvent e);

// The state after `event` in state `from`, or nothing when the transition is not allowed.
std::optional<DeviceState> next_state(DeviceState from, DeviceEvent event);

}  // namespace fibrecell::drivers
