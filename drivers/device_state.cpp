#include "drivers/device_state.hpp"

namespace fibrecell::drivers {

std::string_view to_string(DeviceState s) {
    switch (s) {
        case DeviceState::unconfigured: return "unconfigured";
        case DeviceState::inactive: return "inactive";
        case DeviceState::active: return "active";
        case DeviceState::error: return "error";
    }
    return "?";
}

std::string_view to_string(DeviceEvent e) {
    switch (e) {
        case DeviceEvent::configure: return "configure";
        case DeviceEvent::activate: return "activate";
        case DeviceEvent::deactivate: return "deactivate";
        case DeviceEvent::fault: return "fault";
        case DeviceEvent::clear: return "clear";
        case DeviceEvent::reset: return "reset";
    }
    return "?";
}

std::optional<DeviceState> next_state(DeviceState from, DeviceEvent event) {
    using S = DeviceState;
    using E = DeviceEvent;
    switch (from) {
        case S::unconfigured:
            if (event == E::configure) return S::inactive;
            break;
        case S::inactive:
            if (event == E::activate) return S::active;
            if (event == E::reset) return S::unconfigured;
            if (event == E::fault) return S::error;
            break;
        case S::active:
            if (event == E::deactivate) return S::inactive;
            if (event == E::fault) return S::error;
            break;
        case S::error:
            if (event == E::clear) return S::unconfigured;
            break;
    }
    return std::nullopt;
}

}  // namespace fibrecell::drivers
