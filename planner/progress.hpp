#pragma once
// Progress and cancel for long planner steps, as plain callbacks: the geometry stays unaware of
// threads. The service runs a step on a worker thread and cancels it from a socket command.

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string_view>

namespace fibrecell::planner {

// Thrown by CancelToken::throw_if_cancelled; callers treat it as "stopped on request", not a
// failure.
struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("planning cancelled") {}
};

class CancelToken {
  public:
    void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
    void throw_if_cancelled() const {
        if (cancelled()) throw Cancelled();
    }

  private:
    std::atomic<bool> cancelled_{false};
};

// Loops deep in the geometry (over paths, grid rows, curves) stop a cancelled plan without taking
// its token as a parameter: a stage sets the token for the thread around each piece of work
// (CancelScope, on every thread that runs one) and the loops call cancellation_point(), a load
// and a compare while nothing is cancelled. Geometry code must be exception safe for it (RAII).
namespace detail {
inline thread_local const CancelToken* thread_cancel = nullptr;
}

class CancelScope {
  public:
    explicit CancelScope(const CancelToken* token) : previous_(detail::thread_cancel) {
        detail::thread_cancel = token;
    }
    ~CancelScope() { detail::thread_cancel = previous_; }
    CancelScope(const CancelScope&) = delete;
    CancelScope& operator=(const CancelScope&) = delete;

  private:
    const CancelToken* previous_;
};

// Throws Cancelled when the plan this thread works for was cancelled.
inline void cancellation_point() {
    if (const CancelToken* token = detail::thread_cancel) token->throw_if_cancelled();
}

// stage: stable stage name ("read", "fea", "mst_reorientation", ...); fraction in [0, 1].
using ProgressSink = std::function<void(std::string_view stage, double fraction)>;

// What a long step receives; both members may be left empty.
struct StepControl {
    ProgressSink progress;
    const CancelToken* cancel = nullptr;

    void report(std::string_view stage, double fraction) const {
        if (progress) progress(stage, fraction);
    }
    void check_cancel() const {
        if (cancel) cancel->throw_if_cancelled();
    }
};

}  // namespace fibrecell::planner
