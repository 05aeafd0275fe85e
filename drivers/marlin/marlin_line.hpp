#pragma once
// Framing of host->firmware lines: `N<k> <command>*<checksum>`, the XOR checksum Marlin checks,
// comment stripping and the command classes that decide how long an `ok` may take.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fibrecell::drivers::marlin {

// Marlin keeps MAX_CMD_SIZE = 96 bytes per line including the terminating NUL and silently drops
// characters past 95, which then fails the checksum: a framed line must fit in 95 bytes.
inline constexpr std::size_t max_framed_bytes = 95;

class LineError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

// XOR of every byte of `text` (from `N` up to, not including, the last `*`).
std::uint8_t checksum(std::string_view text);

// Removes `;` and `( ... )` comments and surrounding blanks: "G1 E5 ; prime" -> "G1 E5".
std::string strip_comment(std::string_view gcode);

// "N<line> <command>*<checksum>" without the newline. Throws LineError when the result would not
// fit Marlin's line buffer or the command holds bytes Marlin would interpret (newline, '*').
std::string frame_line(std::int64_t line, std::string_view command);

// How long the firmware may legitimately take before its `ok` (docs/marlin-link.md, "When ok
// comes").
enum class CommandClass {
    normal,        // acknowledged when parsed and executed: M42, M280, T0, M104, ...
    motion,        // G0/G1: the ok waits for a free planner block
    long_running,  // M400, G4, M226, G28, G29, M3/M5: wait for the planner or a pin
    heating,       // M109/M190: minutes; only busy/temperature lines prove liveness
};

CommandClass classify(std::string_view command);
std::string_view to_string(CommandClass c);

// The G/M/T word of a command, upper-case: "M109" for "m109 S200", "" for an empty line.
std::string command_word(std::string_view command);

// M108, M112, M410: handled by Marlin's emergency parser, sent out of band.
bool is_emergency(std::string_view command);

}  // namespace fibrecell::drivers::marlin
