#pragma once
// The robot's event counter as full sequence numbers. The robot puts each event's 1-based sequence
// number mod 65536 on a 16-bit group output (docs/modbus-map.md); this turns the raw values the
// robot I/O link reports back into sequence numbers: a forward difference below 32768 is progress
// (wrapping past 65535 included), an equal value a duplicate, anything else a step back.

#include <cstdint>

namespace fibrecell::daemon::sync {

enum class CounterStep {
    forward,    // to > from; more than one ahead is a gap (missed events to catch up)
    duplicate,  // the value already seen
    reset,      // 0 before any progress: the robot module took the run request
    backwards,  // to < from: the robot and the service disagree (a sync fault)
};

struct CounterAdvance {
    CounterStep step = CounterStep::duplicate;
    std::int64_t from = 0;  // the last sequence before this value
    std::int64_t to = 0;    // the value as a sequence (for `reset`, unchanged: from)
};

class EventCounter {
  public:
    // `last`: the sequence already done (0 on a fresh run; first_event - 1 on a resumed one).
    explicit EventCounter(std::int64_t last) : last_(last) {}

    // Classifies a raw counter value and, when it moves forward, takes it as the new last.
    CounterAdvance advance(std::uint16_t raw);
    std::int64_t last() const { return last_; }

  private:
    std::int64_t last_;
    bool moved_ = false;  // forward progress seen: a 0 is no longer a run-request reset
};

}  // namespace fibrecell::daemon::sync
