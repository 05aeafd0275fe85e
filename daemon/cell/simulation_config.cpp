#include "daemon/cell/simulation_config.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

namespace fibrecell::daemon {

namespace {

std::string printable_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

}  // namespace

SimulationConfig load_simulation_config(config::Section s) {
    SimulationConfig c;
    c.time_scale = s.number("time_scale", c.time_scale, 1, 1000);
    c.hotend_tau_s = s.number("hotend_tau_s", c.hotend_tau_s, 0, 600, true);
    c.residency_s = s.number("residency_s", c.residency_s, 0, 60);
    c.heater_power_w = s.number("heater_power_w", c.heater_power_w, 0, 1000, true);
    c.heater_loss_w_per_k = s.number("heater_loss_w_per_k", c.heater_loss_w_per_k, 0, 100, true);
    c.heater_fan_loss_w_per_k = s.number("heater_fan_loss_w_per_k", c.heater_fan_loss_w_per_k, 0, 100);
    c.heat_capacity_j_per_k = s.number("heat_capacity_j_per_k", c.heat_capacity_j_per_k, 0, 10'000, true);
    c.ambient_c = s.number("ambient_c", c.ambient_c, -40, 80);
    c.board_emergency_parser = s.get_or("board_emergency_parser", c.board_emergency_parser);
    c.main_module = s.get_or<std::string>("main_module", c.main_module);
    c.external_devices = s.choice("devices", "in_process", {"in_process", "external"}) == "external";
    c.external_board = s.choice("board", "mock", {"mock", "external"}) == "external";
    if (c.external_board && c.time_scale != 1)
        s.fail("board", "an external board runs in real time: set simulation.time_scale to 1 (it is " +
                            printable_number(c.time_scale) + ")");
    c.external_board = c.external_board || c.external_devices;
    if (!c.main_module.empty() && !std::filesystem::is_regular_file(c.main_module))
        s.fail("main_module", "no file " + c.main_module);
    s.finish();
    return c;
}

std::string resolve_main_module(const std::string& configured) {
    if (!configured.empty()) return configured;
    for (const char* candidate : {FIBRECELL_INSTALLED_RAPID_DIR "/FcMain.mod",
                                  FIBRECELL_SOURCE_RAPID_DIR "/FcMain.mod"})
        if (std::filesystem::is_regular_file(candidate)) return candidate;
    return FIBRECELL_SOURCE_RAPID_DIR "/FcMain.mod";
}

}  // namespace fibrecell::daemon
