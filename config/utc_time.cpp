#include "config/utc_time.hpp"

#include <chrono>
#include <ctime>

namespace fibrecell::config {

std::string utc_now() { return utc_at(std::chrono::system_clock::now()); }

std::string utc_at(std::chrono::system_clock::time_point at) {
    const std::time_t t = std::chrono::system_clock::to_time_t(at);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

}  // namespace fibrecell::config
