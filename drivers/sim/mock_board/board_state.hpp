#pragma once
// The mock GT2560's state and its firmware loop's steps (mock_gt2560.hpp is the board's face):
// serial.cpp reads and frames what the host sends as Marlin's serial ISR and queue.cpp do,
// commands.cpp runs the commands against the planner and heaters, mock_gt2560.cpp runs the loop
// on its thread and answers the control channel. Everything here runs under `mu`.

#include "drivers/sim/mock_board/mock_gt2560.hpp"
#include "drivers/sim/sim_pty.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

namespace fibrecell::drivers::sim {
namespace mock_board {

using RealClock = std::chrono::steady_clock;

struct Heater {
    double temp_c = 22;
    double target_c = 0;
};

struct Block {
    double end_s = 0;
};

enum class Wait { none, planner_slot, planner_empty, dwell, heating, ok_delay };

struct Exec {
    std::string text;
    std::optional<std::int64_t> line;
    std::string word;
    Wait wait = Wait::none;
    double until_s = 0;  // dwell / ok_delay end
    double dwell_s = 0;  // G4 after the planner drained
    int heater = 0;
    bool wait_cooling = false;
    double in_window_since = -1;
    double started_s = 0;
    double last_busy_s = 0;
    double last_report_s = 0;
    bool ok_pending = true;                          // false once the ok (or M105 reply) went out
    std::optional<double> move_start_s, move_end_s;  // a G0/G1 once queued in the planner
};

}  // namespace mock_board

struct MockGt2560::Impl {
    using RealClock = mock_board::RealClock;
    using Heater = mock_board::Heater;
    using Block = mock_board::Block;
    using Wait = mock_board::Wait;
    using Exec = mock_board::Exec;

    explicit Impl(MockGt2560Options options) : o(std::move(options)), pty(o.link_path) {}

    MockGt2560Options o;
    mutable std::mutex mu;
    mutable std::condition_variable cv;
    std::thread thread;
    std::atomic<bool> stop{false};
    RealClock::time_point t0 = RealClock::now();

    SimPty pty;
    bool unplugged = false;
    bool connected = false;
    bool booting = false;
    bool powered_up = false;              // the first boot says PowerUp, later ones External Reset
    double min_extrude_c = 170;           // EXTRUDE_MINTEMP, M302 S
    bool cold_extrusion_allowed = false;  // M302 P1
    std::uint64_t cold_refusals = 0;
    double boot_until = 0;
    bool silent = false;
    bool killed = false;

    std::deque<char> rx;
    std::string partial;
    bool in_comment = false;
    std::string ep_line;
    bool heat_wait_broken = false;
    std::deque<std::pair<std::string, std::optional<std::int64_t>>> queue;
    std::optional<Exec> current;
    std::int64_t last_n = 0;

    std::deque<Block> planner;
    double last_move_end = 0;
    std::array<double, 2> e_pos{0, 0};
    bool relative_e = false;
    int tool = 0;
    double feed_mm_min = 600;
    std::array<Heater, 3> heaters{};
    double thermal_t = 0;
    double autoreport_s = 0;
    double last_autoreport = 0;
    double keepalive_s = 2;

    std::set<std::int64_t> corrupt, drop, duplicate, swallow;
    // Line k goes into one of the fault sets above (the test's hand on the wire).
    void mark(std::set<std::int64_t>& faults, std::int64_t k) {
        std::lock_guard lock(mu);
        faults.insert(k);
    }
    std::map<std::int64_t, double> delay;
    bool garble_resend = false;
    std::optional<std::int64_t> reset_at;
    std::optional<int> runaway;
    std::vector<std::string> actions;

    std::deque<ExecutedCommand> executed;
    std::deque<PinEvent> pins;
    std::size_t executed_dropped = 0;  // the oldest, past o.max_log
    std::uint64_t dropped = 0;

    double now() const {
        return std::chrono::duration<double>(RealClock::now() - t0).count() * o.time_scale;
    }
    void close_pty() { pty.close(); }

    // A G-code parameter: "S200" in "M109 S200" -> 200.
    static std::optional<double> param(const std::string& cmd, char key);
    static std::string trim(std::string s);

    void open_pty();
    void write_raw(const std::string& bytes);
    void emit(const std::string& line);

    // Power and boot
    void reboot(bool noise, double t);
    // What stock Marlin 1.1.9 on a GT2560 prints when it starts (docs/marlin-link.md).
    void banner();
    void kill(const std::string& reason);

    // Bytes in
    void on_byte(char c);
    // Marlin's emergency parser runs in the RX interrupt, before the byte is stored.
    void scan_emergency(char c);
    // Returns true when `cmd` was an emergency command (acted on).
    bool emergency(const std::string& cmd);

    // Reading lines (queue.cpp)
    void get_serial_commands();
    void on_line(std::string l);
    void line_error(const std::string& what);
    void process_line(const std::string& l);

    // Time: planner and heaters
    void advance(double t);
    std::string temperature_line() const;

    // Executing commands
    void finish(Exec& e, double t);
    void send_ok(Exec& e);
    void pin_event(const std::string& text, double t);
    void begin(Exec& e, double t);
    void queue_move(Exec& e, double t);
    // Returns true when the current command is complete and its ok is out.
    bool progress(Exec& e, double t);
    void step(double t);

    // The firmware loop
    void run();
    // One pass of the firmware loop; returns true while the port is closed (nobody reading).
    bool tick(int fd, short revents, char* buf, std::size_t size);
};

}  // namespace fibrecell::drivers::sim
