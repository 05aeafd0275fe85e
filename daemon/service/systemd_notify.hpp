#pragma once
// The service's side of systemd's Type=notify protocol (sd_notify): READY once the socket API
// listens, STATUS lines an operator sees in `systemctl status`, WATCHDOG pings from the event loop,
// RELOADING/STOPPING around SIGHUP and SIGTERM. Outside systemd (no $NOTIFY_SOCKET) every call
// does nothing, so the same binary runs by hand, in tests and in the demo.

#include <chrono>
#include <optional>
#include <string>

namespace fibrecell::daemon::service {

class SystemdNotifier {
  public:
    SystemdNotifier();

    bool under_systemd() const { return under_systemd_; }
    // Half of WatchdogSec when the unit sets it (ping at least this often), else nothing.
    std::optional<std::chrono::microseconds> watchdog_period() const { return watchdog_period_; }

    void ready(const std::string& status);
    void status(const std::string& status);
    void watchdog();
    void reloading();
    void stopping(const std::string& status);

  private:
    void send(const std::string& state);

    bool under_systemd_ = false;
    std::optional<std::chrono::microseconds> watchdog_period_;
};

}  // namespace fibrecell::daemon::service
