#include "drivers/abb/modbus/input_filters.hpp"

namespace fibrecell::drivers::abb {

bool StableValue::update(std::uint16_t v, IoClock::time_point now, int needed,
                         std::uint64_t& torn) {
    if (accepted && v == *accepted) {
        if (count > 0) ++torn;
        count = 0;
        return false;
    }
    if (count > 0 && v == candidate) {
        ++count;
    } else {
        if (count > 0) ++torn;
        candidate = v;
        count = 1;
        first_read = now;
    }
    if (count < needed) return false;
    accepted = v;
    count = 0;
    return true;
}

RobotHeartbeatWatch::Reading RobotHeartbeatWatch::read(bool level, IoClock::time_point now) {
    Reading r;
    if (!last_) {
        last_ = level;
    } else if (level != *last_) {
        if (edge_since_connect_)
            r.gap_ms = std::chrono::duration<double, std::milli>(now - last_edge_).count();
        last_ = level;
        last_edge_ = now;
        armed_ = true;
        edge_since_connect_ = true;
        lost_reported_ = false;
    }
    const auto still = now - last_edge_;
    r.still_ms = std::chrono::duration_cast<std::chrono::milliseconds>(still).count();
    r.ok = armed_ && edge_since_connect_ && still <= timeout_;
    if (armed_ && still > timeout_ && !lost_reported_) {
        lost_reported_ = true;
        r.lost_now = true;
    }
    return r;
}

void RobotHeartbeatWatch::reconnected(IoClock::time_point now) {
    last_.reset();
    last_edge_ = now;
    edge_since_connect_ = false;
    lost_reported_ = false;
}

}  // namespace fibrecell::drivers::abb
