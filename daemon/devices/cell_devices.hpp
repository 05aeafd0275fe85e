#pragma once
// The cell's devices as the service holds them for its whole life: the GT2560 link and the
// extruder controller, the IRC5's Robot Web Services client and the Modbus robot I/O link. On a
// simulated cell (cell YAML `simulated: true`) it also runs the devices themselves in-process — the
// mock GT2560 on a pseudo-terminal and the simulated IRC5 on loopback — and points the same
// drivers at them: simulation replaces the devices, never the driver code.
//
// The links' observers are set once, here; the running print receives them through set_print().

#include "daemon/cell/cell_config.hpp"
#include "daemon/print/print_session.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/rws/rws_client.hpp"
#include "drivers/extruder/extruder_controller.hpp"
#include "drivers/marlin/marlin_link.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

namespace fibrecell::drivers::sim {
class MockGt2560;
class SimCell;
}  // namespace fibrecell::drivers::sim

namespace fibrecell::daemon::devices {

class DeviceError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct HotendTemps {
    std::optional<double> pla_c, pla_target_c, ccf_c, ccf_target_c;
};

class CellDevices {
  public:
    // Starts the simulated devices when the cell is simulated; connects nothing yet.
    explicit CellDevices(const CellConfig& cell);
    ~CellDevices();
    CellDevices(const CellDevices&) = delete;
    CellDevices& operator=(const CellDevices&) = delete;

    // Activates the board link and starts the robot I/O link (which reconnects by itself);
    // waits up to `timeout` for both. Throws DeviceError naming the device and why. Calling it
    // again re-activates a board that fell out. A robot program run found still going with no
    // print of this service's is aborted (end_orphan_run).
    void connect(std::chrono::milliseconds timeout);
    // Disconnects both links (the service is stopping).
    void disconnect();

    print::PrintLinks links();
    drivers::ExtruderController& extruder() { return extruder_; }
    drivers::abb::RobotIoLink& robot_io() { return *robot_io_; }
    drivers::marlin::MarlinLink& board() { return board_; }

    // The running print gets the links' events (robot counter, link state, temperatures); null
    // when none runs. Waits for an event being delivered to the previous one.
    void set_print(print::PrintSession* session);

    // M112 out of band and the robot's abort and pause requests. Not a safety function: both
    // travel through software that may be stuck; the cell's E-stop chain is the safety function.
    void estop();

    bool simulated() const { return cell_.simulated; }
    double time_scale() const { return time_scale_; }
    drivers::sim::SimCell* sim_cell() { return sim_cell_.get(); }
    drivers::sim::MockGt2560* mock_board() { return mock_board_.get(); }

    HotendTemps temperatures() const;
    // {"board": {...}, "robot": {...}} for cell.status (no device I/O: cached values only).
    nlohmann::json status() const;

  private:
    void end_orphan_run(std::chrono::milliseconds timeout);

    void temperature(const drivers::marlin::TemperatureReport& report);

    CellConfig cell_;
    double time_scale_ = 1;
    std::unique_ptr<drivers::sim::MockGt2560> mock_board_;
    std::unique_ptr<drivers::sim::SimCell> sim_cell_;
    drivers::marlin::MarlinLink board_;
    drivers::ExtruderController extruder_;
    std::unique_ptr<drivers::abb::rws::RwsClient> rws_;
    std::unique_ptr<drivers::abb::RobotIoLink> robot_io_;

    mutable std::mutex mu_;  // guards print_ and temps_
    print::PrintSession* print_ = nullptr;
    HotendTemps temps_;
};

}  // namespace fibrecell::daemon::devices
