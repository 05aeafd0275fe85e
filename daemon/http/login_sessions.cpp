#include "daemon/http/login_sessions.hpp"

#include <sys/random.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace fibrecell::http {

namespace {

constexpr auto kWindow = std::chrono::minutes(1);
constexpr std::size_t kMaxTrackedAddresses = 4096;  // a bound on memory under a spray of addresses

std::string random_hex(std::size_t bytes) {
    std::array<unsigned char, 64> raw{};
    std::size_t got = 0;
    while (got < bytes) {
        const ssize_t n = ::getrandom(raw.data() + got, bytes - got, 0);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error(std::string("getrandom: ") + std::strerror(errno));
        }
        got += static_cast<std::size_t>(n);
    }
    static constexpr char digits[] = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < bytes; ++i) {
        out += digits[raw[i] >> 4];
        out += digits[raw[i] & 15];
    }
    return out;
}

}  // namespace

std::string SessionTable::open(Clock::time_point now) {
    for (auto it = expiry_.begin(); it != expiry_.end();)
        it = it->second <= now ? expiry_.erase(it) : std::next(it);
    while (!expiry_.empty() && expiry_.size() >= max_sessions_) {
        auto oldest = expiry_.begin();
        for (auto it = expiry_.begin(); it != expiry_.end(); ++it)
            if (it->second < oldest->second) oldest = it;
        expiry_.erase(oldest);
    }
    std::string id = random_hex(32);
    expiry_[id] = now + lifetime_;
    return id;
}

bool SessionTable::valid(const std::string& id, Clock::time_point now) {
    const auto it = expiry_.find(id);
    if (it == expiry_.end()) return false;
    if (it->second <= now) {
        expiry_.erase(it);
        return false;
    }
    return true;
}

void LoginGuard::forget_old(Clock::time_point now) {
    while (!all_failures_.empty() && all_failures_.front() + kWindow <= now) all_failures_.pop_front();
    for (auto it = failures_.begin(); it != failures_.end();) {
        auto& times = it->second;
        while (!times.empty() && times.front() + kWindow <= now) times.pop_front();
        it = times.empty() ? failures_.erase(it) : std::next(it);
    }
}

std::optional<std::chrono::seconds> LoginGuard::wait_for(const std::string& address,
                                                         Clock::time_point now) {
    forget_old(now);
    const auto total = static_cast<std::size_t>(limit_) * kAddressesPerLimit;
    if (all_failures_.size() >= total)
        return std::chrono::ceil<std::chrono::seconds>(all_failures_.front() + kWindow - now);
    const auto it = failures_.find(address);
    if (it == failures_.end() || it->second.size() < static_cast<std::size_t>(limit_))
        return std::nullopt;
    const auto left = it->second.front() + kWindow - now;
    return std::chrono::ceil<std::chrono::seconds>(left);
}

void LoginGuard::failed(const std::string& address, Clock::time_point now) {
    forget_old(now);
    if (failures_.size() >= kMaxTrackedAddresses && !failures_.contains(address))
        failures_.erase(failures_.begin());
    failures_[address].push_back(now);
    all_failures_.push_back(now);
}

std::string cookie_value(std::string_view header, std::string_view name) {
    while (!header.empty()) {
        const auto end = header.find(';');
        std::string_view pair = header.substr(0, end);
        header = end == std::string_view::npos ? std::string_view{} : header.substr(end + 1);
        while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
        const auto eq = pair.find('=');
        if (eq == std::string_view::npos || pair.substr(0, eq) != name) continue;
        std::string_view value = pair.substr(eq + 1);
        while (!value.empty() && value.back() == ' ') value.remove_suffix(1);
        return std::string(value);
    }
    return "";
}

}  // namespace fibrecell::http
