#pragma once
// The extruder board link: a serial port, the Marlin protocol engine and the device lifecycle
// (drivers/device_state.hpp). It owns one I/O thread running Boost.Asio; every public method is
// safe to call from any other thread. Callbacks run on the I/O thread and must not block.
//
//   configure -> activate: open the port, wait for the `start` banner (opening resets an Arduino
//   board), `N0 M110 N0` and its ok, M115 capabilities, M155 auto-report
//   submit: numbered lines, resends and timeouts handled inside; the future says done or why not
//   a fault (firmware reset, halt, lost link, timeouts) fails every request and moves the device
//   to `error`; clear() then configure() + activate() reconnect.

#include "drivers/device_state.hpp"
#include "drivers/marlin/feed_ledger.hpp"
#include "drivers/marlin/marlin_protocol.hpp"
#include "drivers/marlin/serial_settings.hpp"

#include <atomic>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::drivers::marlin {

struct MarlinLinkConfig {
    SerialSettings serial;
    ProtocolSettings protocol;
    Seconds boot_timeout{3.0};         // wait for `start` after open; go on without it
    Seconds handshake_timeout{5.0};    // M110 reset and M115 each
    int autoreport_interval_s = 1;     // M155 S<n> when the firmware has AUTOREPORT_TEMP; 0 off
};

struct CommandOutcome {
    LinkFailure failure = LinkFailure::none;
    std::string detail;
    bool ok() const { return failure == LinkFailure::none; }
};

class LinkError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class MarlinLink {
  public:
    MarlinLink();
    ~MarlinLink();
    MarlinLink(const MarlinLink&) = delete;
    MarlinLink& operator=(const MarlinLink&) = delete;

    DeviceState state() const { return state_.load(); }

    // Lifecycle hooks; each throws LinkError when the transition is not allowed in the current
    // state. activate() throws SerialError/LinkError when the port or handshake fails (the
    // device then stays inactive).
    void configure(MarlinLinkConfig config);
    void activate();
    void deactivate();
    void clear();  // error -> unconfigured (an operator acknowledged the fault)

    // Queues G-code lines (comments stripped, blank lines skipped). Completes when the firmware
    // acknowledged the last one, or with the failure that stopped it. Throws LineError naming the
    // offending line (index and text) before anything is queued.
    std::future<CommandOutcome> submit(const std::vector<std::string>& gcode);

    // Drops every queued, unsent line (their requests complete as `aborted`) and sends M108 out
    // of band, which breaks an M109/M190 wait. Lines already in the firmware still run.
    void abort();
    // M410 out of band: the planner is flushed (E positions are then unknown: G92 E0).
    void quick_stop();
    // M112 out of band: the firmware kills itself and needs a reset. NOT a safety function: it
    // travels over USB through a firmware that may be stuck; the cell's E-stop chain is.
    void emergency_stop();

    std::map<std::string, bool> capabilities() const;  // from M115 `Cap:` lines
    // Whether the firmware acts on M108/M112/M410 as the bytes arrive (Cap:EMERGENCY_PARSER:1).
    // Stock Marlin 1.1.9 does not: they wait behind a blocking M109/M400, so abort() cannot break
    // a heat-up and emergency_stop() is obeyed only after it (docs/marlin-link.md).
    bool emergency_parser() const;
    ProtocolStats stats() const;
    // Filament each extruder took over the link's life (every session), from acknowledged lines.
    FeedTotals fed() const;
    LinkFailure fault() const;
    std::string fault_detail() const;
    // When the link failed (a firmware reset: when its `start` came); empty while it has not.
    std::optional<Clock::time_point> fault_time() const;

    // Observers (set before activate()).
    void on_temperature(std::function<void(const TemperatureReport&)> f);
    void on_reply(std::function<void(const Reply&)> f);
    void on_bytes_written(std::function<void()> f);  // benchmark: request-to-wire latency

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::atomic<DeviceState> state_{DeviceState::unconfigured};
    void transition(DeviceEvent e);
};

}  // namespace fibrecell::drivers::marlin
