#pragma once
// Internal, per client: the rate limit for Delivery::latest events. Per (topic, method) at most
// one line per interval goes out; in between only the newest line is held, and it is sent when
// the interval ends, so the client always ends up with the latest value. Runs on the strand.

#include "daemon/api/server_core.hpp"

#include <boost/asio/steady_timer.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace fibrecell::api {

class LatestOnlyGate {
  public:
    using Line = std::shared_ptr<const std::string>;
    using Send = std::function<void(const Line&)>;
    enum class Outcome { sent, held, replaced };

    LatestOnlyGate(Strand strand, std::chrono::nanoseconds interval, Send send);
    ~LatestOnlyGate();
    LatestOnlyGate(const LatestOnlyGate&) = delete;
    LatestOnlyGate& operator=(const LatestOnlyGate&) = delete;

    Outcome offer(const std::string& topic, const std::string& method, Line line);
    // Sends the held lines of `topic` now (an in-order event of that topic is about to go out).
    void flush_topic(const std::string& topic);
    // Forgets held lines whose topic `keep` rejects (after an unsubscribe).
    void drop_unless(const std::function<bool(const std::string& topic)>& keep);
    void set_interval(std::chrono::nanoseconds interval);
    void cancel();  // drops everything held; no more sends

  private:
    struct Slot {
        std::string topic;
        Line held;
        std::chrono::steady_clock::time_point last_sent{};
        std::unique_ptr<boost::asio::steady_timer> timer;
        bool armed = false;
        std::uint64_t generation = 0;  // of the armed wait; stale handlers are ignored
    };
    void send_held(Slot& slot);
    void on_timer(const std::string& key, std::uint64_t generation);

    Strand strand_;
    std::chrono::nanoseconds interval_;
    Send send_;
    std::uint64_t next_generation_ = 1;
    std::map<std::string, Slot> slots_;                       // key: topic + '\n' + method
    std::shared_ptr<char> alive_ = std::make_shared<char>();  // timer handlers check it
};

}  // namespace fibrecell::api
