#pragma once
// The feed the board has acknowledged but, by its feed rate, not run yet. Marlin answers `ok`
// to a G1 once it is planned, not once it has moved: a reset of the MCU loses what it had planned
// and the host is never told how much. Each acknowledged piece is taken to start when the board
// took it or when the one before it ends, whichever is later, and to run for its path time, so
// what was still queued at the moment of a reset can be fed again (docs/sync-engine.md).

#include "daemon/sync/feed_meter.hpp"

#include <deque>

namespace fibrecell::daemon::sync {

class BoardFeedQueue {
  public:
    // A piece of `e_mm` the board acknowledged at `at`, running for `run_s` real seconds.
    void acknowledged(double e_mm, double run_s, SteadyClock::time_point at);
    // The part of the acknowledged feed not run by `t` (a running piece counts in proportion).
    double unrun_at(SteadyClock::time_point t) const;

  private:
    struct Planned {
        SteadyClock::time_point start, end;
        double e_mm;
    };
    std::deque<Planned> planned_;  // only pieces that may still be running
};

}  // namespace fibrecell::daemon::sync
