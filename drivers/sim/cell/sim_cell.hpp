#pragma once
// The simulated cell controller: an IRC5 with its RAPID task, the robot's motion and the Modbus I/O
// coupler, served on loopback like the real cell (docs/simcell.md). One SimClock drives the motion
// simulator and the RapidTask; SimController serves them over Robot Web Services (RwsServer, digest
// auth); CellSignals wires the task's I/O to the coupler (RobotIoServer). Tests use it in-process;
// tools/fibrecell-simcell is the standalone program.
//
//   SimCell cell({.time_scale = 20, .main_module = source_dir + "/drivers/abb/rapid/FcMain.mod"});
//   RwsClient rws({.port = cell.rws_port()});     // FcMain loaded, task stopped with PP at main
//   RobotIoLink io({.port = cell.modbus_port(), ...});
//
// Nothing here may be shared between cells: make one per test.

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/modbus/robot_io_config.hpp"
#include "drivers/sim/robot_io/robot_io_server.hpp"
#include "drivers/sim/rws/rws_server.hpp"
#include "drivers/sim/cell/cell_signals.hpp"
#include "drivers/sim/cell/sim_controller.hpp"
#include "drivers/sim/cell/task_log.hpp"
#include "drivers/sim/motion/motion_simulator.hpp"
#include "drivers/sim/rapid_exec/rapid_task.hpp"
#include "drivers/sim/sim_clock.hpp"

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

struct SimCellOptions {
    double time_scale = 1;  // simulated seconds per real second
    // Address, port (0: ephemeral), user and password of the RWS server.
    rws::RwsServerConfig rws;
    // The coupler's register map (the cell YAML's robot_io.map) and where it listens.
    abb::RobotIoMap io_map;
    std::string io_address = "127.0.0.1";
    int io_port = 0;  // 0: ephemeral
    // Shortest real time between two robot heartbeat edges passed to the coupler (see
    // cell_signals.hpp).
    std::chrono::milliseconds robot_heartbeat_filter{10};
    MotionOptions motion;       // arm variant, solver margins, acceleration, start joints
    abb::RobotSignals signals;  // the EIO signal names (robot.signals of the cell YAML)
    // The resident main module loaded at start-up from this file (the repo's
    // drivers/abb/rapid/FcMain.mod); empty: an empty task.
    std::filesystem::path main_module;
    std::string main_module_home_path = "fibrecell/FcMain.mod";  // where it is put in HOME:
    // After loading: start RAPID (PP at main, running) instead of leaving it stopped at main.
    bool start_main = false;
    // Every task message, as it happens (on the task's or the motion thread; must not block).
    std::function<void(const TaskLogEntry&)> on_task_log;
};

class SimCell {
  public:
    // Binds both servers and loads the main module. Throws std::runtime_error naming the file
    // and every build error when the main module does not load, and what the servers throw when
    // a port cannot be bound.
    explicit SimCell(SimCellOptions options);
    ~SimCell();  // servers closed first, then the task and the motion thread stopped
    SimCell(const SimCell&) = delete;
    SimCell& operator=(const SimCell&) = delete;

    std::uint16_t rws_port() const;
    int modbus_port() const;
    const SimClock& clock() const { return clock_; }

    // Inspection.
    TaskStatus task_status() const;
    std::vector<TaskLogEntry> task_log() const { return log_->entries(); }
    bool wait_for_log(const std::string& text, std::chrono::milliseconds timeout) const {
        return log_->wait_for(text, timeout);
    }
    MotionStatus motion_status() const { return motion_->status(); }
    TrajectorySample robot() const { return motion_->current(); }
    // The TCP trajectory since start-up or the last take (samples carry simulated and steady
    // clock time; clock() maps between them).
    std::vector<TrajectorySample> take_trajectory() { return motion_->take_trajectory(); }
    // Every write to a robot output (events, barriers, running), oldest first.
    std::vector<SignalWrite> output_history() const { return signals_.output_history(); }

    // Fault knobs.
    // Closes every Modbus connection and refuses new ones for `d` (the coupler's cable pulled).
    void drop_modbus_link(std::chrono::milliseconds d);
    // RAPID stops as on a controller error; the error shows in task_status() and over RWS.
    void stop_with_error(const std::string& text);
    // Motors off (as a guard stop): motion halted, queue dropped, RAPID stopped; RWS start is
    // refused until motors_on().
    void motors_off();
    void motors_on();

    // The parts, for what the knobs above do not cover.
    SimController& controller() { return *controller_; }
    RobotIoServer& coupler() { return *coupler_; }
    rws::RwsServer& rws_server() { return *rws_; }
    MotionSimulator& motion() { return *motion_; }
    RapidTask& task() { return *task_; }

  private:
    void load_main_module();
    void shutdown() noexcept;  // servers, then the task, then motion; idempotent

    SimCellOptions options_;
    SimClock clock_;
    std::unique_ptr<TaskLog> log_;
    std::unique_ptr<MotionSimulator> motion_;
    CellSignals signals_;
    std::shared_ptr<SimController> controller_;
    std::unique_ptr<RapidTask> task_;
    std::unique_ptr<RobotIoServer> coupler_;
    std::unique_ptr<rws::RwsServer> rws_;
};

}  // namespace fibrecell::drivers::sim
