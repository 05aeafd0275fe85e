#pragma once
// Parsing of firmware->host lines (docs/marlin-link.md, "What the firmware prints"): ok (plain,
// ADVANCED_OK, M105 reply), resend requests in Marlin's and older firmwares' spellings, busy
// keepalives, echo/Error lines, temperature reports, the boot banner, host actions and M115
// capabilities.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibrecell::drivers::marlin {

struct TemperatureReading {
    std::string sensor;             // "T", "T0", "T1", "B", "C"
    double actual_c = 0;
    std::optional<double> target_c;
};

struct TemperatureReport {
    std::vector<TemperatureReading> readings;
    std::optional<double> wait_left_s;  // " W:12" during M109/M190 residency, absent for "W:?"
    const TemperatureReading* find(std::string_view sensor) const;
};

enum class ReplyKind {
    empty,         // blank or NUL noise only
    ok,            // "ok", "ok N12 P15 B3", "ok T:..."
    resend,        // "Resend: 12", "Resend:12", "rs N12"
    busy,          // "echo:busy: processing" (also without "echo:")
    wait,          // "wait" (NO_TIMEOUTS builds)
    line_error,    // checksum / line-number errors that precede a resend request
    error,         // any other "Error:..." (see is_fatal)
    echo,          // "echo:..."
    temperature,   // " T:21.0 /0.0 B:..." auto-report or heat-up progress
    start,         // "start": the firmware has just (re)booted; also after a line the reset cut
    action,        // "//action:pause"
    capability,    // "Cap:AUTOREPORT_TEMP:1"
    firmware_info, // "FIRMWARE_NAME:Marlin ..."
    other,
};

struct Reply {
    ReplyKind kind = ReplyKind::other;
    std::string text;                     // the line without NULs and line ends
    std::optional<std::int64_t> line;     // ok N.., Resend N, or "Last Line: N" of a line error
    std::optional<int> planner_free;      // ok P..
    std::optional<int> buffer_free;       // ok B..
    std::optional<TemperatureReport> temperatures;
    bool fatal = false;                   // error: the firmware has halted (kill / stop)
    std::string capability;               // capability: name; action: the action text
    bool capability_on = false;
    // start: what the firmware had sent of its last line when the reset cut it ("ok T:25.5 /0"
    // before "start" on one line); empty when `start` came on a line of its own.
    std::string cut_line;
};

Reply parse_reply(std::string_view line);

// " T:210.0 /210.0 B:60 /60 T0:... @:0 W:?" -> readings; nothing when no `X:number` pair is found.
std::optional<TemperatureReport> parse_temperatures(std::string_view text);

std::string_view to_string(ReplyKind k);

}  // namespace fibrecell::drivers::marlin
