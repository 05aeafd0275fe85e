#pragma once
// What the robot I/O link makes of the robot's inputs before it believes them (robot_io_link.cpp):
// a group value counts only once it read the same on several polls in a row (a group read can
// tear between the coupler's two updates of its words, docs/modbus-map.md), and the robot's
// heartbeat must keep toggling once it has been seen. Link thread only.

#include <chrono>
#include <cstdint>
#include <optional>

namespace fibrecell::drivers::abb {

using IoClock = std::chrono::steady_clock;

// A 16-bit value that counts only once `needed` polls in a row read it.
struct StableValue {
    std::optional<std::uint16_t> accepted;
    std::uint16_t candidate = 0;
    int count = 0;  // polls in a row that read `candidate`; 0 restarts the count (a reconnect)
    IoClock::time_point first_read{};

    // True when `v` became the accepted value with this read; `torn` counts abandoned candidates.
    bool update(std::uint16_t v, IoClock::time_point now, int needed, std::uint64_t& torn);
};

// The watch on the robot program's heartbeat (FcMain toggles it every timer tick). It is armed by
// the first edge ever seen: before that the robot program may simply not run yet, which the start
// of a print checks by itself. Once armed, a heartbeat that stays still past the timeout is lost,
// reported once, until it toggles again; the watch of a new connection starts with that connection.
class RobotHeartbeatWatch {
  public:
    explicit RobotHeartbeatWatch(IoClock::duration timeout) : timeout_(timeout) {}

    struct Reading {
        bool ok = false;               // armed, toggled on this connection, within the timeout
        bool lost_now = false;         // past the timeout: true on the first such read only
        long long still_ms = 0;        // since the last edge (or the connection, or a restart)
        std::optional<double> gap_ms;  // an edge on this read: the time since the one before
    };
    Reading read(bool level, IoClock::time_point now);

    bool armed() const { return armed_; }
    // A new connection: its first read only takes the level.
    void reconnected(IoClock::time_point now);
    // The service itself did not run for a while: the heartbeat went unread, not missing.
    void restart_age(IoClock::time_point now) { last_edge_ = now; }

  private:
    IoClock::duration timeout_;
    std::optional<bool> last_;
    IoClock::time_point last_edge_{};
    bool armed_ = false;
    bool edge_since_connect_ = false;
    bool lost_reported_ = false;
};

}  // namespace fibrecell::drivers::abb
