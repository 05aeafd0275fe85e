#pragma once
// Tests wait on the event they mean, never on the clock: a condition polled until it holds. The
// deadline only bounds a failure; it is generous so that a loaded or slow machine still passes.
//
//   ASSERT_TRUE(eventually([&] { return link.state() == DeviceState::active; }));
//   // "nothing happens": wait for a later event that proves the point was passed, e.g.
//   ASSERT_TRUE(eventually([&] { return clock.now_s() >= stopped_at_s + 0.4; }));

#include <chrono>
#include <thread>

namespace fibrecell::test {

inline constexpr std::chrono::milliseconds eventually_timeout{20'000};

// True as soon as `condition()` holds; false if it still does not when `timeout` has passed.
// `every`: the pause between two checks (longer for a costly check: a file read, an API call).
template <class Condition>
bool eventually(Condition&& condition, std::chrono::milliseconds timeout = eventually_timeout,
                std::chrono::milliseconds every = std::chrono::milliseconds(1)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        if (condition()) return true;
        if (std::chrono::steady_clock::now() >= deadline) return condition();
        std::this_thread::sleep_for(every);
    }
}

}  // namespace fibrecell::test
