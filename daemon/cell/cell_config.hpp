#pragma once
// The cell configuration (cell YAML): what the service needs before it can run. Each module
// reads its own section; unknown keys and out-of-range values are rejected with the key path.

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/modbus/robot_io_config.hpp"
#include "drivers/abb/rws/rws_config.hpp"
#include "drivers/extruder/extruder_config.hpp"
#include "daemon/cell/part_limits.hpp"
#include "daemon/cell/simulation_config.hpp"

#include "config/yaml_section.hpp"

#include <functional>
#include <string>

namespace fibrecell::daemon {

struct CellConfig {
    std::string name = "cell-1";                    // shown in status and logs
    std::string log_level = "info";                 // trace|debug|info|warn|error|off
    std::string state_dir = "/var/lib/fibrecelld";  // job folders live here
    bool simulated = true;                          // simulated controller and mock board
    drivers::ExtruderConfig extruder;               // GT2560 link, tools, cutter (marlin-link.md)
    drivers::abb::RobotCellConfig robot;            // IRB 1200, bed, head (robot-program.md)
    drivers::abb::rws::RwsLinkConfig rws;           // the IRC5's Robot Web Services (rws-link.md)
    drivers::abb::RobotIoConfig robot_io;           // Modbus TCP robot I/O coupler (robot-io.md)
    SimulationConfig simulation;                    // the simulated cell (simulated: true)
    PartLimits part_limits;                         // the largest part it takes (service.md)
};

// The sections only the service reads (api:, jobs:, print:, queue:); other readers of a cell YAML
// (`fibrecell plan --cell`) pass over them.
inline constexpr const char* service_sections[] = {"api", "jobs", "print", "queue", "history", "spools"};

// Loads and validates a cell YAML file; throws config::ConfigError naming the key. `service`
// reads the service's own sections from the root (fibrecelld); without it they are skipped.
CellConfig load_cell_config(const std::string& path,
                            const std::function<void(config::Section& root)>& service = {});

}  // namespace fibrecell::daemon
