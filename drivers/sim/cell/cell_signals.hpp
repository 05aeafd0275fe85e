#pragma once
// The simulated cell's wiring between the Modbus coupler (RobotIoServer, docs/modbus-map.md) and
// the IRC5 I/O the RAPID task sees (EIO signals, docs/irc5-setup.md):
//   coupler outputs -> IRC5 inputs: barrier_release -> giFcRelease, pause_request -> diFcPause,
//                                   abort_request -> diFcAbort, heartbeat_out -> diFcHeartbeat;
//   IRC5 outputs -> coupler inputs: goFcEvent -> event_number, goFcBarrier -> barrier_number,
//                                   doFcRunning -> robot_running, doFcHeartbeat -> heartbeat_in.
// Names come from the cell's RobotSignals and are matched as RAPID does (case-insensitive).
//
// An input change reaches the task through `on_input` (RapidTask::signal_changed); an output write
// reaches the coupler at once. FcMain toggles doFcHeartbeat every 0.1 s of simulated time, which
// at a high time scale is faster than any poll: the coupler passes a heartbeat edge only when
// `heartbeat_filter` (real time) has passed since the last one, like a digital input filter.
// Every output write but the heartbeat's is kept, with its time, for tests (output_history();
// the last `max_history` of them).

#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/sim/robot_io/robot_io_server.hpp"

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

struct SignalWrite {
    std::string signal;  // as configured ("goFcEvent")
    double value = 0;
    std::chrono::steady_clock::time_point wall;
};

class CellSignals {
  public:
    CellSignals(abb::RobotSignals names, std::chrono::milliseconds heartbeat_filter);

    // Connects the coupler (not owned; it must outlive detach()) and takes its current commands
    // as the input values.
    void attach(RobotIoServer& coupler);
    // Where input changes go (signal name as configured, new value). Called on the coupler's
    // thread, never while this object's locks are held by the caller.
    void on_input(std::function<void(const std::string& signal, double value)> f);
    // Stops forwarding in both directions; returns once no forward is in progress.
    void detach();

    // The coupler's commands changed (RobotIoServer::on_commands).
    void commands_changed(const ServiceCommands& c);

    // TaskIo: the value of any of the eight signals; std::out_of_range for another name.
    double read(const std::string& signal) const;
    // TaskIo: SetDO/SetGO/trigger outputs; std::out_of_range for an unknown signal,
    // std::invalid_argument for an input or a value that does not fit the signal.
    void write(const std::string& signal, double value);

    std::vector<std::string> names() const { return names_.all(); }
    std::vector<SignalWrite> output_history() const;

  private:
    enum class Id { release, pause, abort, heartbeat_in, event, barrier, running, heartbeat_out };
    Id find(const std::string& signal) const;
    void set_input(Id id, double value, std::vector<std::pair<std::string, double>>& changes);

    abb::RobotSignals names_;
    std::chrono::milliseconds heartbeat_filter_;
    std::map<std::string, Id> ids_;  // folded name -> signal

    mutable std::mutex values_mu_;  // values_, history_, coupler_, last_hb_edge_
    std::map<Id, double> values_;
    std::deque<SignalWrite> history_;
    static constexpr std::size_t max_history = 100'000;
    RobotIoServer* coupler_ = nullptr;
    std::chrono::steady_clock::time_point last_hb_edge_{};

    // Held while an input change is forwarded, so that detach() can wait for it.
    std::mutex forward_mu_;
    std::function<void(const std::string&, double)> on_input_;
};

}  // namespace fibrecell::drivers::sim
