#include "daemon/sync/event_counter.hpp"

namespace fibrecell::daemon::sync {

CounterAdvance EventCounter::advance(std::uint16_t raw) {
    constexpr std::int64_t modulus = 65536;
    const std::int64_t forward = ((raw - last_) % modulus + modulus) % modulus;
    if (forward == 0) return {CounterStep::duplicate, last_, last_};
    // FcMain writes 0 when it takes a run request: before any progress a 0 is that, even when a
    // resumed run's baseline sits just below a wrap.
    if (raw == 0 && !moved_) return {CounterStep::reset, last_, last_};
    if (forward < modulus / 2) {
        const CounterAdvance a{CounterStep::forward, last_, last_ + forward};
        last_ = a.to;
        moved_ = true;
        return a;
    }
    return {CounterStep::backwards, last_, last_ - (modulus - forward)};
}

}  // namespace fibrecell::daemon::sync
