#pragma once
// Turns the board's replies (MarlinLink::submit futures) into calls on a sink, in submission
// order, as soon as each completes, so that the engine's worker can sleep on its own queue instead
// of polling futures. One thread; MarlinLink completes requests in the order they were submitted,
// so waiting on the oldest one first loses no time.

#include "drivers/marlin/marlin_link.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

namespace fibrecell::daemon::sync {

class ReplyWatcher {
  public:
    // ticket: the caller's number for the request; at: when its completion was seen.
    using Sink = std::function<void(std::uint64_t ticket, const drivers::marlin::CommandOutcome&,
                                    std::chrono::steady_clock::time_point at)>;

    explicit ReplyWatcher(Sink sink);
    ~ReplyWatcher();  // stops watching (pending requests are abandoned) and joins
    ReplyWatcher(const ReplyWatcher&) = delete;
    ReplyWatcher& operator=(const ReplyWatcher&) = delete;

    void watch(std::uint64_t ticket, std::future<drivers::marlin::CommandOutcome> reply);

  private:
    void run();

    struct Pending {
        std::uint64_t ticket;
        std::future<drivers::marlin::CommandOutcome> reply;
    };
    Sink sink_;
    std::mutex mu_;
    std::condition_variable cv_;
    std::deque<Pending> pending_;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace fibrecell::daemon::sync
