#pragma once
// When the hotends go off (docs/service.md, "Heaters"). A print that ends (completed, aborted, or
// nothing left to print) turns them off at once, unless the cell keeps them hot for
// `hold_after_print` for a back-to-back print; a paused job's go off after `paused_timeout` (the
// resume heats them again); a cell with no job on it and a heater on turns it off after
// `idle_timeout`, whatever heated it. The policy only decides and explains (for cell.status and
// the dashboard); the print runner sends the M104s and reports back.

#include <nlohmann/json_fwd.hpp>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace fibrecell::daemon::printer {

struct HeaterPolicyOptions {
    std::chrono::milliseconds hold_after_print{0};
    std::chrono::milliseconds paused_timeout{std::chrono::minutes(30)};
    std::chrono::milliseconds idle_timeout{std::chrono::minutes(10)};
};

class HeaterPolicy {
  public:
    using Clock = std::chrono::steady_clock;

    HeaterPolicy(HeaterPolicyOptions options, Clock::time_point now);

    void printing(std::int64_t job);  // started or resumed: on, for the job
    void paused(std::int64_t job, Clock::time_point now);
    // The job's print ended: `outcome` ("completed", "aborted by the operator", ...).
    void ended(std::int64_t job, const std::string& outcome, Clock::time_point now);

    // What the board's last temperature report said: a target above 0 on either hotend. An idle
    // cell's heaters are switched off only when they are on (timed from when it was first seen);
    // the others are sent off whatever the last report said.
    void observe(bool heating, Clock::time_point now);
    // Why the heaters are to go off now, or nullopt.
    std::optional<std::string> due(Clock::time_point now) const;
    // The M104 S0s for `reason` went to the board.
    void switched_off(const std::string& reason, Clock::time_point now);

    // {"on", "why" (why they are on; null when off), "off_in_s" (null: not while printing),
    // "last_off" (why they last went off; null: not yet)}.
    nlohmann::json status(Clock::time_point now) const;

  private:
    enum class Mode { idle, printing, paused, held };

    std::optional<Clock::time_point> off_at() const;

    HeaterPolicyOptions options_;
    Mode mode_ = Mode::idle;
    std::int64_t job_ = 0;
    std::string outcome_;                      // held: how the job ended
    Clock::time_point since_;                  // paused, held: since when
    bool heating_ = false;                     // as last observed
    std::optional<Clock::time_point> idle_heating_since_;  // idle: first seen heating
    bool sent_ = false;                        // paused, held: off already sent
    std::string last_off_;
    std::optional<Clock::time_point> off_sent_at_;
};

}  // namespace fibrecell::daemon::printer
