#pragma once
// The robot I/O link's settings: where the Modbus TCP coupler is, how often it is polled, the
// heartbeats both ways, reconnect back-off, and the register map (docs/modbus-map.md for the
// signals, docs/robot-io.md for the `robot_io:` keys). Addresses are 0-based, as on the wire.

#include "config/yaml_section.hpp"

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace fibrecell::drivers::abb {

// The four Modbus data tables. Coils and holding registers are written by the service (and can be
// read back); discrete inputs and input registers are read-only.
enum class ModbusTable { coil, discrete_input, holding_register, input_register };

std::string_view to_string(ModbusTable t);
bool is_bit_table(ModbusTable t);

// Where one signal lives. A 1-bit signal can also sit in bit `bit` (0 = least significant) of a
// register, as on a coupler that shows its inputs both as discrete inputs and as input registers.
struct ModbusAddress {
    ModbusTable table = ModbusTable::input_register;
    int address = 0;         // 0..65535, 0-based ("input register 0" = documentation 30001)
    std::optional<int> bit;  // only for 1-bit signals in a register table
};

// One entry per signal of docs/modbus-map.md; the defaults are that page's map.
struct RobotIoMap {
    // Robot -> service (IRC5 outputs -> coupler inputs; the service reads).
    ModbusAddress event_number{ModbusTable::input_register, 0};    // goFcEvent, 16 bit
    ModbusAddress barrier_number{ModbusTable::input_register, 1};  // goFcBarrier, 16 bit
    ModbusAddress robot_running{ModbusTable::discrete_input, 32};  // doFcRunning
    ModbusAddress heartbeat_in{ModbusTable::discrete_input, 33};   // doFcHeartbeat
    // Service -> robot (coupler outputs -> IRC5 inputs; the service writes).
    ModbusAddress barrier_release{ModbusTable::holding_register, 0};  // giFcRelease, 16 bit
    ModbusAddress pause_request{ModbusTable::coil, 16};               // diFcPause
    ModbusAddress abort_request{ModbusTable::coil, 17};               // diFcAbort
    ModbusAddress heartbeat_out{ModbusTable::coil, 18};               // diFcHeartbeat
    // Number of the last chunk ready on the controller (16 bit). Not wired in the default design
    // (all chunks are uploaded before the run request): absent unless the YAML maps it.
    std::optional<ModbusAddress> chunk_ready;
};

struct RobotIoConfig {
    std::string host = "127.0.0.1";  // coupler address or name
    int port = 502;
    int unit_id = 1;                              // Modbus unit (slave) id sent with every request
    std::chrono::microseconds poll_period{2000};  // inputs read this often
    std::chrono::milliseconds response_timeout{250};          // per request, and per connect
    std::chrono::milliseconds heartbeat_period{100};          // heartbeat_out toggled this often
    std::chrono::milliseconds robot_heartbeat_timeout{1000};  // no heartbeat_in edge = robot lost
    int stable_reads = 2;  // polls in a row that must agree before a 16-bit value counts
    std::chrono::milliseconds reconnect_backoff_min{100};
    std::chrono::milliseconds reconnect_backoff_max{5000};
    bool pause_on_fault = true;  // a fault sets pause_request; only set_pause(false) clears it
    // When > 0, heartbeat_out toggles only while RobotIoLink::service_alive() was called within
    // this time (the heartbeat then proves the service loop is alive, not just this thread).
    std::chrono::milliseconds service_watchdog{0};
    std::chrono::seconds stats_log_period{60};  // robot_io.stats line; 0 = never
    RobotIoMap map;
};

// Reads a `robot_io:` section; throws config::ConfigError naming the key (range, unknown keys,
// a table a signal cannot use, two signals on one address).
RobotIoConfig load_robot_io_config(config::Section s);

// The checks above for a config built in code; throws std::invalid_argument.
void validate(const RobotIoConfig& c);

// "input register 0", "discrete input 33", "input register 2 bit 1".
std::string describe(const ModbusAddress& a);

}  // namespace fibrecell::drivers::abb
