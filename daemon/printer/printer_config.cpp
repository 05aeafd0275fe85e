#include "daemon/printer/printer_config.hpp"

namespace fibrecell::daemon::printer {

PrintRunnerOptions load_print_options(config::Section s) {
    PrintRunnerOptions o;
    using ms = std::chrono::milliseconds;
    o.connect_timeout = ms(static_cast<long>(1000 * s.number("connect_timeout_s", 10, 0.1, 600)));
    o.heartbeat_timeout =
        ms(static_cast<long>(1000 * s.number("heartbeat_timeout_s", 1, 0.2, 60)));
    const auto minutes = [&](const char* key, double fallback, double low) {
        return ms(static_cast<long>(60000 * s.number(key, fallback, low, 24 * 60)));
    };
    o.heaters.paused_timeout = minutes("heater_timeout_min", 30, 0.01);
    o.heaters.hold_after_print = minutes("heater_hold_min", 0, 0);
    o.heaters.idle_timeout = minutes("idle_heater_timeout_min", 10, 0.01);
    o.realtime_priority = s.integer("realtime_priority", 20, 0, 99);
    o.late_cut_mm = s.number("late_cut_mm", o.late_cut_mm, 0, 1000, true);
    s.finish();
    return o;
}

}  // namespace fibrecell::daemon::printer
