#pragma once
// A GT2560 running stock Marlin 1.1.9 (its messages, capabilities and limits: docs/marlin-link.md,
// "The mock and Marlin 1.1.9"), simulated behind a pseudo-terminal (openpty): the driver opens the
// slave side exactly like /dev/ttyUSB0. It follows the firmware as docs/marlin-link.md describes ("The
// host protocol, from the firmware's side", "Mock board"): reset on open and boot banner,
// line-number/checksum/resend rules, a 128-byte RX ring that drops bytes when full, a 4-line
// command buffer, a 16-block planner whose moves take (scaled) real time, two hotends and a bed
// with a first-order thermal model, blocking waits with temperature and busy lines, pin/servo
// events, M112 kill and the emergency parser.
//
// Faults are injected from a control channel (these methods; the mock-gt2560 tool maps its stdin
// onto them), never in-band G-code. All times in the logs are simulated seconds.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fibrecell::drivers::sim {

struct MockGt2560Options {
    double time_scale = 1.0;          // simulated seconds per real second
    double bootloader_s = 1.0;        // silence after a reset before `start`
    bool reset_on_open = true;        // DTR auto-reset: every open of the port reboots the board
    bool resend_ok = true;            // bugfix-2.1.x prints ok after Resend; older builds do not
    // Stock Marlin 1.1.9 for the GT2560: M108/M112/M410 act only when their line is read (not
    // while a command blocks). true: a build with EMERGENCY_PARSER, where they act on arrival.
    bool emergency_parser = false;
    bool advanced_ok = false;         // ok N<n> P<planner free> B<buffer free>
    int rx_buffer_bytes = 128;
    int command_buffer_lines = 4;     // BUFSIZE
    int planner_blocks = 16;          // BLOCK_BUFFER_SIZE
    double ambient_c = 22.0;
    double hotend_tau_s = 40.0;       // first-order time constants
    double bed_tau_s = 90.0;
    double temp_window_c = 1.0;       // TEMP_WINDOW / TEMP_BED_WINDOW
    double residency_s = 10.0;        // TEMP_RESIDENCY_TIME
    double keepalive_s = 2.0;         // DEFAULT_KEEPALIVE_INTERVAL
    double min_extrude_temp_c = 170;  // PREVENT_COLD_EXTRUSION's EXTRUDE_MINTEMP; 0: off (M302 P1)
    std::string link_path;            // optional stable symlink to the slave (survives replug)
    // Executed commands and pin events kept for observation, each; 0: all. A board that runs for
    // long (in the service, the mock-gt2560 tool) keeps a bound: the oldest are dropped.
    std::size_t max_log = 0;
};

struct ExecutedCommand {
    double t_s = 0;                   // simulated time the handler returned
    std::optional<std::int64_t> line; // its N, when it was numbered
    std::string text;                 // the command without N and checksum
    // A G0/G1 runs later, when the planner gets to it: its motion's start and end [simulated s].
    std::optional<double> move_start_s, move_end_s;
    std::size_t number = 0;           // 0, 1, ... in the order commands executed
};

// M42 / M280 / M3 / M5 as they took effect, with the planner state at that moment.
struct PinEvent {
    double t_s = 0;
    std::string command;              // "M42 P11 S255"
    int planner_blocks_pending = 0;   // moves queued or running when the pin changed
    double last_move_end_s = 0;       // end of the latest move ever queued
};

class MockGt2560 {
  public:
    explicit MockGt2560(MockGt2560Options options = {});
    ~MockGt2560();
    MockGt2560(const MockGt2560&) = delete;
    MockGt2560& operator=(const MockGt2560&) = delete;

    // The device path for the driver: the symlink when configured, else /dev/pts/N.
    std::string port_path() const;
    double sim_now_s() const;
    // The steady-clock instant of a simulated time of this board (its logs' t_s), to line its
    // log up with other simulated devices.
    std::chrono::steady_clock::time_point wall_at(double sim_s) const;

    // Fault injection, keyed by the host's line number K (each fires once).
    void corrupt_line(std::int64_t k);      // one byte flipped: checksum error
    void drop_line(std::int64_t k);         // the whole line vanishes
    void duplicate_line(std::int64_t k);    // the line is processed twice
    void swallow_ok(std::int64_t k);        // executed, ok never sent
    void delay_ok(std::int64_t k, double sim_s);
    void garble_next_resend();              // the next Resend carries a wrong number
    void reset_at_line(std::int64_t k);     // brown-out when line K arrives (NULs, then boot)
    void reset_now();
    void go_silent(bool silent);            // ignore input, send nothing
    void unplug();                          // close the pty master (cable pull)
    void replug();                          // a new pty behind the same link_path; boots on open
    void thermal_runaway(int heater);       // 0, 1 = hotends, 2 = bed
    void send_action(const std::string& action);  // "//action:<action>"

    // Observation. Commands are numbered 0, 1, ... in the order they executed; executed_count()
    // counts them all, executed() and executed_since() return those still kept (max_log).
    std::vector<ExecutedCommand> executed() const;
    std::size_t executed_count() const;
    std::vector<ExecutedCommand> executed_since(std::size_t first) const;
    std::vector<PinEvent> pin_events() const;
    double temperature_c(int heater) const;
    double target_c(int heater) const;  // 0: the heater is off
    bool killed() const;
    std::uint64_t rx_bytes_dropped() const;
    std::uint64_t cold_extrusion_refusals() const;  // E moves refused below min_extrude_temp_c
    // Waits until at least `n` commands have executed; false on timeout (real time).
    bool wait_for_executed(std::size_t n, std::chrono::milliseconds timeout) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::sim
