#pragma once
// The service's Modbus TCP link to the robot I/O coupler (docs/robot-io.md, docs/modbus-map.md).
// It owns one thread that, every poll period, writes the outputs that changed, reads the robot's
// inputs, toggles the service heartbeat and watches the robot's. It reports, and decides nothing
// about the job: the framework turns a fault into a cell fault (drivers/device_state.hpp) and
// decides when to resume.
//
//   connecting --connected--> up --I/O error or robot heartbeat lost--> fault
//        ^                                                               |
//        +-- (initial connect failures stay here)    fault --recovered--> up
//
// In `fault` the link reconnects with exponential back-off (a lost connection) or keeps polling (a
// lost robot heartbeat); it is `up` again once a poll succeeds and, if the robot heartbeat had been
// seen before, the heartbeat toggled again. Every public method is safe from any thread. Callbacks
// run on the link thread and must not block (they delay the next poll); a change's callback runs
// before the snapshot shows it (so after wait_until_up() the `up` callback has run).

#include "drivers/abb/modbus/robot_io_config.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::abb {

using IoClock = std::chrono::steady_clock;

enum class RobotIoState {
    stopped,     // start() not called yet, or stop() called
    connecting,  // never connected since start(); `last_error` says why not yet
    up,          // connected, polls succeed, the robot heartbeat is not lost
    fault,       // connection lost or robot heartbeat lost; `fault_reason` says which
};

std::string_view to_string(RobotIoState s);

class RobotIoError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// One accepted change of the robot's event counter (goFcEvent). Values are raw (mod 65536): the
// sync engine handles wrap, gaps and duplicates.
struct EventCounterChange {
    std::optional<std::uint16_t> previous;  // empty for the first value after start()
    std::uint16_t value = 0;
    std::uint16_t barrier = 0;       // barrier_number as read in the same poll
    IoClock::time_point first_read;  // the poll that first read `value`
    IoClock::time_point accepted;    // after `stable_reads` polls agreed (callback time)
};

// What the service currently commands (whether or not it has reached the coupler yet).
struct RobotIoOutputs {
    std::uint16_t release = 0;
    bool pause = false;
    bool abort = false;
    bool heartbeat = false;
    std::uint16_t chunk_ready = 0;
};

struct RobotIoStats {
    std::uint64_t polls = 0;           // successful poll cycles
    std::uint64_t requests = 0;        // Modbus requests answered (reads and writes)
    std::uint64_t writes = 0;          // output writes
    std::uint64_t event_changes = 0;   // accepted event counter changes
    std::uint64_t torn_reads = 0;      // 16-bit reads discarded by the stable_reads filter
    std::uint64_t events_dropped = 0;  // changes lost because nobody drained take_events()
    std::uint64_t faults = 0;          // transitions into `fault`
    std::uint64_t connects = 0;        // successful connections
    std::uint64_t connect_failures = 0;
    double poll_us_last = 0;  // duration of the last poll cycle (all its requests)
    double poll_us_max = 0;
    // Worst cases within a connection, what the timeouts are chosen from (docs/robot-io.md):
    // the longest time between two heartbeat_out toggles (FcMain holds the robot beyond its
    // heartbeat timeout) and between two heartbeat_in edges seen.
    double heartbeat_gap_ms_max = 0;
    double robot_heartbeat_gap_ms_max = 0;
};

struct RobotIoSnapshot {
    RobotIoState state = RobotIoState::stopped;
    bool connected = false;
    std::string fault_reason;  // why the link is in `fault` ("" otherwise)
    std::string last_error;    // the latest I/O or connect error, kept after recovery
    // Robot -> service, as last accepted (stable) values.
    std::uint16_t event_counter = 0;
    std::uint16_t barrier = 0;
    bool running = false;
    bool robot_heartbeat_ok = false;  // toggled within robot_heartbeat_timeout
    IoClock::time_point last_poll{};  // last successful poll
    RobotIoOutputs outputs;
    RobotIoStats stats;
};

struct RobotIoStateChange {
    RobotIoState from = RobotIoState::stopped;
    RobotIoState to = RobotIoState::stopped;
    std::string reason;  // the fault reason, or what recovered ("reconnected after 1.2 s")
    IoClock::time_point at;
};

class RobotIoLink {
  public:
    // Throws std::invalid_argument for a config that fails validate().
    explicit RobotIoLink(RobotIoConfig config);
    ~RobotIoLink();  // stop()
    RobotIoLink(const RobotIoLink&) = delete;
    RobotIoLink& operator=(const RobotIoLink&) = delete;

    // Observers; set before start(). Called on the link thread, in order.
    void on_event(std::function<void(const EventCounterChange&)> f);
    void on_state(std::function<void(const RobotIoStateChange&)> f);

    // Starts the link thread (it connects in the background); stop() joins it. Both idempotent;
    // stop() returns within about one response timeout.
    void start();
    void stop();

    // Waits until the link is `up`; false on timeout.
    bool wait_until_up(std::chrono::milliseconds timeout) const;

    RobotIoSnapshot snapshot() const;
    RobotIoState state() const;

    // Accepted event counter changes since the last call, oldest first (the queue keeps the last
    // 4096; older ones are counted in stats().events_dropped). An alternative to on_event().
    std::vector<EventCounterChange> take_events();

    // Outputs: written on the link thread as soon as they change (not waiting for the next poll),
    // and all rewritten after every reconnect, pause_request first.
    void set_release(std::uint16_t barrier);
    void set_pause(bool on);
    void set_abort(bool on);
    // Throws RobotIoError when map.chunk_ready is not configured.
    void set_chunk_ready(std::uint16_t n);

    // The service loop calls this regularly when config.service_watchdog > 0.
    void service_alive();

    const RobotIoConfig& config() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::abb
