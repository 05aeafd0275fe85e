#pragma once
// The Modbus TCP side of the simulated controller: a libmodbus server on loopback that serves the
// robot I/O map (docs/modbus-map.md) like the coupler of the real cell. The simulated robot sets
// its outputs (event number, barrier number, running, heartbeat) through this thread-safe API and
// reads what the service commanded; tests and the simulator use the fault knobs to drop, refuse or
// ignore connections.
//
// The server binds its own listening socket (port 0 = an ephemeral port chosen by the kernel, read
// back with port()), accepts connections itself and hands each accepted socket to libmodbus only
// for framing and answering, all on one thread. With `two_view` (the default) it shows each
// process image two ways like most couplers: coil n is bit n%16 of holding register n/16, discrete
// input n is bit n%16 of input register n/16.

#include "drivers/abb/modbus/robot_io_config.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace fibrecell::drivers::sim {

struct RobotIoServerOptions {
    std::string bind_address = "127.0.0.1";  // IPv4 address to listen on
    int port = 0;                            // 0: an ephemeral port (see port())
    bool two_view = true;                    // coils <-> holding registers, DIs <-> IRs
    // The simulated robot's heartbeat_in toggles this often from start-up (FcMain: 100 ms);
    // 0 = only when toggle_robot_heartbeat() is called.
    std::chrono::milliseconds robot_heartbeat_period{100};
    int max_connections = 8;  // more are accepted and closed at once
};

// What the service has commanded, as the simulated robot sees it.
struct ServiceCommands {
    std::uint16_t release = 0;
    bool pause = false;
    bool abort = false;
    bool heartbeat = false;
    std::uint16_t chunk_ready = 0;                              // 0 when not mapped
    std::uint64_t heartbeat_edges = 0;                          // changes of heartbeat_out seen
    std::chrono::steady_clock::time_point last_heartbeat_edge;  // when the last one was seen
};

struct RobotIoServerStats {
    std::uint64_t connections_accepted = 0;
    std::uint64_t connections_open = 0;
    std::uint64_t requests = 0;  // requests received (answered or not)
    std::uint64_t writes = 0;    // write requests answered
};

class RobotIoServer {
  public:
    // Binds and starts serving; throws RobotIoError when the address cannot be bound, and
    // std::invalid_argument for a map that fails validate().
    explicit RobotIoServer(abb::RobotIoMap map, RobotIoServerOptions options = {});
    ~RobotIoServer();  // closes every connection and joins the server thread
    RobotIoServer(const RobotIoServer&) = delete;
    RobotIoServer& operator=(const RobotIoServer&) = delete;

    int port() const;
    const std::string& host() const;

    // The robot's side (robot -> service signals).
    void set_event_number(std::uint16_t n);
    void set_barrier_number(std::uint16_t n);
    void set_running(bool on);
    void toggle_robot_heartbeat();
    // Starts or stops the automatic robot heartbeat (fault knob: the robot program stops).
    void set_robot_heartbeat_running(bool on);

    ServiceCommands commands() const;
    // Waits until `pred(commands())` holds; false on timeout.
    bool wait_for_commands(const std::function<bool(const ServiceCommands&)>& pred,
                           std::chrono::milliseconds timeout) const;
    // Called on the server thread after every write request that changed a command. It must not
    // block nor call the fault knobs.
    void on_commands(std::function<void(const ServiceCommands&)> f);

    // Fault knobs. Each takes effect before it returns.
    void drop_connections();                                   // closes all (with a reset)
    void refuse_connections_for(std::chrono::milliseconds d);  // no listener for `d`
    void set_answering(bool on);  // false: requests are read and never answered
    // The next `reads` read requests that cover event_number see `value` instead (a torn read of
    // the 16-bit group, docs/modbus-map.md "Torn reads").
    void inject_torn_event_reads(std::uint16_t value, int reads);

    RobotIoServerStats stats() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::sim
