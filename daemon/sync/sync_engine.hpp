#pragma once
// The sync engine: one per print. It follows the robot's event counter and drives the extruder
// board to match (docs/sync-engine.md): a head switch selects the tool and waits for its hotend, a
// fibre start threads the fibre, then releases the robot's barrier and meters the fibre feed along
// the path; extrude_on/off prime, meter and retract PLA; a cut stops the feed and fires the cutter.
// Events are taken strictly in order (16-bit wrap, duplicates, gaps caught up, a step back is a
// fault); barriers are released only after the board acknowledged its part and not while paused.
// Any fault (a failed board request, the robot I/O link in fault, the counter going back) stops
// metering, aborts the board's queue, asks the robot to pause and is reported once; the last
// confirmed event stays in status() so that a new engine can resume after it.
//
// The engine does not take over the links' observer slots (one per link, owned by the service):
// the service forwards them. Inputs may come from any thread and never block.
//
//   SyncEngine engine(program, extruder, marlin, robot_io, {.pla_line_width_mm = 0.8});
//   robot_io.on_event([&](const auto& c) { engine.robot_event(c); });     // before robot_io.start()
//   robot_io.on_state([&](const auto& c) { engine.robot_link_state(c); });
//   marlin.on_temperature([&](const auto& r) { engine.board_temperature(r); });
//   engine.on_event_done([&](const EventDone& d) { journal(d.sequence); });
//   engine.start();

#include "daemon/sync/sync_options.hpp"
#include "daemon/sync/sync_status.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/extruder/extruder_controller.hpp"
#include "drivers/marlin/marlin_link.hpp"

#include <functional>
#include <memory>
#include <string>

namespace fibrecell::daemon::sync {

class SyncEngine {
  public:
    // The program, extruder controller and links must outlive the engine; the board link is
    // active and the robot I/O link started (or about to start). Throws std::invalid_argument for
    // options that fail validate().
    SyncEngine(const drivers::abb::PrintProgram& program, drivers::ExtruderController& extruder,
               drivers::marlin::MarlinLink& board, drivers::abb::RobotIoLink& robot,
               SyncOptions options = {});
    ~SyncEngine();  // stop()
    SyncEngine(const SyncEngine&) = delete;
    SyncEngine& operator=(const SyncEngine&) = delete;

    // Observers; set before start(). They run on the engine's worker thread, in event order, and
    // should return quickly (metering waits for them).
    void on_event_done(std::function<void(const EventDone&)> f);
    void on_fault(std::function<void(const std::string& reason)> f);
    void on_progress(std::function<void(const SyncProgress&)> f);  // after each layer_end

    // Starts the worker (once per engine): the board gets relative E and both hotend targets
    // (prepare without waiting), then events are followed. Inputs that came before start() are
    // kept and handled in order.
    void start();
    // Joins the worker. Sends nothing to the devices: pause or fault first to stop the cell.
    void stop();

    // Inputs, forwarded by the service from the links' observers (any thread, never block).
    void robot_event(const drivers::abb::EventCounterChange& change);
    void robot_link_state(const drivers::abb::RobotIoStateChange& change);
    void board_temperature(const drivers::marlin::TemperatureReport& report);

    // Pause: no more metered feed is sent (the board finishes what it has, at most about lead_s of
    // path) and the robot is asked to stop; barriers done meanwhile stay held. Resume continues
    // the metering where it stopped and releases a held barrier. Both asynchronous (see status()).
    // Resume after a fault does nothing: start a new engine after the last confirmed event.
    void pause();
    void resume();

    SyncStatus status() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::daemon::sync
