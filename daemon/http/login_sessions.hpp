#pragma once
// Who is logged in to the dashboard, and who has guessed the token too often (docs/dashboard.md).
// Plain bookkeeping with the time passed in, so that tests need no clock; the HTTP listener
// holds one of each behind its mutex.

#include <chrono>
#include <cstddef>
#include <deque>
#include <map>
#include <optional>
#include <string>

namespace fibrecell::http {

using Clock = std::chrono::steady_clock;

// Session cookies: random 256-bit ids, each valid for `lifetime` after its login.
class SessionTable {
  public:
    SessionTable(std::chrono::seconds lifetime, std::size_t max_sessions)
        : lifetime_(lifetime), max_sessions_(max_sessions) {}

    // A new session id (64 hex digits from the kernel's random source). The oldest session goes
    // when max_sessions are open.
    std::string open(Clock::time_point now);
    bool valid(const std::string& id, Clock::time_point now);
    void close(const std::string& id) { expiry_.erase(id); }
    void close_all() { expiry_.clear(); }
    std::chrono::seconds lifetime() const { return lifetime_; }
    std::size_t size() const { return expiry_.size(); }

  private:
    std::chrono::seconds lifetime_;
    std::size_t max_sessions_;
    std::map<std::string, Clock::time_point, std::less<>> expiry_;
};

// Wrong tokens per client address in a sliding minute: past the limit, logins from that
// address are refused without looking at the token until the oldest failure is a minute old.
// All addresses together have a limit too (`kAddressesPerLimit` times the address's): many
// addresses (a whole loopback range, a botnet) do not add up to more guesses.
class LoginGuard {
  public:
    static constexpr int kAddressesPerLimit = 4;

    explicit LoginGuard(int failures_per_minute) : limit_(failures_per_minute) {}

    // How long the address must wait; nullopt when it may try now.
    std::optional<std::chrono::seconds> wait_for(const std::string& address, Clock::time_point now);
    void failed(const std::string& address, Clock::time_point now);
    void succeeded(const std::string& address) { failures_.erase(address); }
    void set_limit(int failures_per_minute) { limit_ = failures_per_minute; }

  private:
    void forget_old(Clock::time_point now);

    int limit_;
    std::map<std::string, std::deque<Clock::time_point>> failures_;
    std::deque<Clock::time_point> all_failures_;  // every address's, in the window
};

// The value of cookie `name` in a Cookie header ("a=1; fibrecell_session=ab12"), or "".
std::string cookie_value(std::string_view header, std::string_view name);

}  // namespace fibrecell::http
