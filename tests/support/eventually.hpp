#pragma once
// Tests wait on the event they mean, never on the clock: a condition polled until it holds. The
// deadline only bounds a failure; it is generous so that a loaded or slow machine still passes.
//
//   ASSERT_TRUE(eventually([&] { return link.state() == DeviceState::active; }));
//   // "nothing happens": wait for a later event that proves the point was passed, e.g.
//   ASSERT_TRUE(eventually([&] { return clock.now_s() >= stopped_at_s + 0.4; }));

#include <algorithm>
#include <chrono>
#include <thread>

namespace fibrecell::test {

inline constexpr std::chrono::milliseconds eventually_timeout{20'000};

// True as soon as `condition()` holds; false if it still does not when `timeout` has passed.
// `every`: the first pause between two checks (longer for a costly check: a file read, an API
// call). The pause then doubles up to `slowest` (or stays at `every` when that is longer): a
// condition met at once is seen at once, and a long wait does not keep a service under ASan busy
// answering a poll every millisecond.
template <class Condition>
bool eventually(Condition&& condition, std::chrono::milliseconds timeout = eventually_timeout,
                std::chrono::milliseconds every = std::chrono::milliseconds(1),
                std::chrono::milliseconds slowest = std::chrono::milliseconds(10)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    const auto longest = std::max(every, slowest);
    for (auto pause = every;; pause = std::min(2 * pause, longest)) {
        if (condition()) return true;
        if (std::chrono::steady_clock::now() >= deadline) return condition();
        std::this_thread::sleep_for(pause);
    }
}

}  // namespace fibrecell::test
