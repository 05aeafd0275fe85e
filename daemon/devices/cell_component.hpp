#pragma once
// Cell, the component that owns the cell's devices and their links (docs/layout.md,
// "Components"): the GT2560 link and extruder controller, the robot's RWS and Modbus links, and on
// a simulated cell the simulated devices (CellDevices). It answers cell.status and cell.estop and
// publishes notify.cell_status twice a second, each time proving to the robot's heartbeat that
// the service's loop runs.
//
// Hooks for the components above it:
//   add_status_part  what cell.status says besides the devices (the printer: heaters, job,
//                    progress, sync); called on the API's strand.
//   on_estop         cell.estop sent M112 and the robot's abort: the printer aborts its print.

#include "daemon/cell/cell_config.hpp"
#include "daemon/component/component.hpp"
#include "daemon/devices/cell_devices.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <vector>

namespace fibrecell::daemon::devices {

struct CellComponentOptions {
    std::chrono::milliseconds connect_timeout{10000};  // the devices at the service's start
    int realtime_priority = 20;  // SCHED_FIFO of the devices' time-critical threads; 0: off
};

class CellComponent : public component::Component {
  public:
    using StatusPart = std::function<void(nlohmann::json& status)>;

    CellComponent(boost::asio::io_context& io, const CellConfig& cell, CellComponentOptions options);
    ~CellComponent() override;

    void add_status_part(StatusPart part);      // before start()
    void on_estop(std::function<void()> after);  // before start()

    void register_endpoints(component::Endpoints& endpoints) override;
    void start() override;  // the devices (a simulated cell's start here), not connected yet
    void serve() override;  // connects them (one that is not there yet is reported, not fatal)
    void stop() override;   // disconnects them

    CellDevices& devices() { return *devices_; }  // after start()
    nlohmann::json status() const;                 // what cell.status answers

  private:
    void tick();

    CellConfig cell_;
    CellComponentOptions options_;
    component::Endpoints endpoints_;
    std::vector<StatusPart> status_parts_;
    std::vector<std::function<void()>> on_estop_;
    std::unique_ptr<CellDevices> devices_;
    boost::asio::steady_timer ticker_;
    bool stopping_ = false;
};

}  // namespace fibrecell::daemon::devices
