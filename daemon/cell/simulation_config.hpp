#pragma once
// The `simulation:` section of the cell YAML: how the simulated cell behaves when `simulated: true`
// (docs/service.md). The robot, its RAPID task, the mock board and its heaters all run on one
// time scale, so a print of an hour shows in minutes; the service's own timing (heartbeats,
// time-outs) stays in real time.
//
//   simulation:
//     time_scale: 20        # simulated seconds per real second (1..1000)
//     hotend_tau_s: 8       # the mock hotends' first-order time constant (simulated s)
//     residency_s: 2        # M109's residency in the temperature window (simulated s)
//     heater_power_w: 40    # gt2560-avr's hotends (drivers/sim/avr/hotend_thermal.hpp): the
//     heater_loss_w_per_k: 0.05        # cartridge at full duty, the loss in still air, what the
//     heater_fan_loss_w_per_k: 0.04    # part fan adds at full duty, the block's heat capacity
//     heat_capacity_j_per_k: 10        # (time constant C/k = 200 s) and the air; the mock
//     ambient_c: 25                    # board uses hotend_tau_s instead
//     board_emergency_parser: true     # the mock board's firmware is built with EMERGENCY_PARSER,
//                                      # as the cell's should be; false: stock Marlin 1.1.9
//     main_module: ""       # FcMain.mod to load; empty: the installed one, else the source tree's
//     devices: in_process   # or external: fibrecell-simcell and mock-gt2560 run as their own
//                           # processes at the addresses of the rws:, robot_io: and extruder: sections
//     board: mock           # or external: the robot stays simulated in-process, the board is the
//                           # one at extruder.link.port (gt2560-avr running a firmware, or a real
//                           # GT2560); it runs in real time, so time_scale must be 1

#include "config/yaml_section.hpp"

#include <cstddef>
#include <string>

namespace fibrecell::daemon {

struct SimulationConfig {
    double time_scale = 20;
    double hotend_tau_s = 8;
    double residency_s = 2;
    double heater_power_w = 40;
    double heater_loss_w_per_k = 0.05;
    double heater_fan_loss_w_per_k = 0.04;
    double heat_capacity_j_per_k = 10;
    double ambient_c = 25;
    bool board_emergency_parser = true;
    std::string main_module;
    bool external_devices = false;  // devices: external
    bool external_board = false;    // board: external (also true with devices: external)
    // Not in the YAML: trajectory samples the in-process simulated robot keeps until taken. The
    // service never takes them, so it keeps few; a test that measures along the path keeps all.
    std::size_t trajectory_samples = 10'000;
};

// Throws config::ConfigError naming the key ("simulation.time_scale").
SimulationConfig load_simulation_config(config::Section s);

// The FcMain.mod the simulated cell loads: `configured` when set, else the installed copy
// (<datadir>/fibrecell/rapid/FcMain.mod), else the source tree's drivers/abb/rapid/FcMain.mod.
std::string resolve_main_module(const std::string& configured);

}  // namespace fibrecell::daemon
