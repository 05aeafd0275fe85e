#include "daemon/service/systemd_notify.hpp"

#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include <cstdint>
#include <cstdlib>
#include <ctime>

namespace fibrecell::daemon::service {

SystemdNotifier::SystemdNotifier() {
    under_systemd_ = std::getenv("NOTIFY_SOCKET") != nullptr;
    std::uint64_t usec = 0;
    if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0)
        watchdog_period_ = std::chrono::microseconds(usec / 2);
}

void SystemdNotifier::send(const std::string& state) {
    if (!under_systemd_) return;
    const int r = sd_notify(0, state.c_str());
    if (r < 0) spdlog::warn("systemd.notify_failed state={} errno={}", state, -r);
}

void SystemdNotifier::ready(const std::string& s) { send("READY=1\nSTATUS=" + s); }
void SystemdNotifier::status(const std::string& s) { send("STATUS=" + s); }
void SystemdNotifier::watchdog() { send("WATCHDOG=1"); }

void SystemdNotifier::reloading() {
    // systemd 253+ wants the monotonic time with RELOADING=1; older ones ignore it.
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    const auto usec = static_cast<std::uint64_t>(ts.tv_sec) * 1'000'000u +
                      static_cast<std::uint64_t>(ts.tv_nsec) / 1000u;
    send("RELOADING=1\nMONOTONIC_USEC=" + std::to_string(usec));
}

void SystemdNotifier::stopping(const std::string& s) { send("STOPPING=1\nSTATUS=" + s); }

}  // namespace fibrecell::daemon::service
