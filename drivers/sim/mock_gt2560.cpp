#include "drivers/sim/mock_gt2560.hpp"

#include "config/thread_priority.hpp"
#include "drivers/marlin/marlin_line.hpp"
#include "drivers/sim/sim_pty.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>

namespace fibrecell::drivers::sim {
namespace {

using RealClock = std::chrono::steady_clock;

// A G-code parameter: "S200" in "M109 S200" -> 200.
std::optional<double> param(const std::string& cmd, char key) {
    for (std::size_t i = 1; i < cmd.size(); ++i) {
        if (cmd[i] == key && cmd[i - 1] == ' ') {
            try {
                return std::stod(cmd.substr(i + 1));
            } catch (const std::exception&) {
                return std::nullopt;
            }
        }
    }
    return std::nullopt;
}

std::string trim(std::string s) {
    while (!s.empty() && s.front() == ' ') s.erase(s.begin());
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

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
    double until_s = 0;         // dwell / ok_delay end
    double dwell_s = 0;         // G4 after the planner drained
    int heater = 0;
    bool wait_cooling = false;
    double in_window_since = -1;
    double started_s = 0;
    double last_busy_s = 0;
    double last_report_s = 0;
    bool ok_pending = true;     // false once the ok (or M105 reply) went out
    std::optional<double> move_start_s, move_end_s;  // a G0/G1 once queued in the planner
};

}  // namespace

struct MockGt2560::Impl {
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
    bool powered_up = false;           // the first boot says PowerUp, later ones External Reset
    double min_extrude_c = 170;        // EXTRUDE_MINTEMP, M302 S
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

    void open_pty() {
        pty.open();
        unplugged = false;
        connected = false;
    }

    void close_pty() { pty.close(); }

    void write_raw(const std::string& bytes) {
        if (pty.master() < 0 || !connected) return;
        std::size_t off = 0;
        while (off < bytes.size()) {
            const ssize_t n = ::write(pty.master(), bytes.data() + off, bytes.size() - off);
            if (n <= 0) return;  // host not reading: a real UART would lose it too
            off += static_cast<std::size_t>(n);
        }
    }

    void emit(const std::string& line) {
        if (silent) return;
        write_raw(line + "\n");
    }

    // --- Power and boot -------------------------------------------------------------------

    void reboot(bool noise, double t) {
        rx.clear();
        partial.clear();
        in_comment = false;
        ep_line.clear();
        queue.clear();
        current.reset();
        planner.clear();
        for (auto& h : heaters) h.target_c = 0;
        last_n = 0;
        autoreport_s = 0;
        min_extrude_c = o.min_extrude_temp_c;
        cold_extrusion_allowed = o.min_extrude_temp_c <= 0;
        keepalive_s = o.keepalive_s;
        relative_e = false;
        tool = 0;
        killed = false;
        if (noise && !silent) write_raw(std::string("\0\0\xff\0", 4));
        booting = true;
        boot_until = t + o.bootloader_s;
    }

    // What stock Marlin 1.1.9 on a GT2560 prints when it starts (docs/marlin-link.md).
    void banner() {
        emit("start");
        emit(powered_up ? "echo: External Reset" : "echo:PowerUp");
        powered_up = true;
        emit("Marlin 1.1.9");
        emit("echo: Last Updated: 2018-08-01 | Author: (none, default config)");
        emit("Compiled: Aug  1 2018");
        emit("echo: Free Memory: 4264  PlannerBufferBytes: 1232");
        emit("echo:EEPROM version mismatch");
        emit("echo:Hardcoded Default Settings Loaded");
    }

    void kill(const std::string& reason) {
        if (!reason.empty()) emit("Error:" + reason);
        emit("Error:Printer halted. kill() called!");
        killed = true;
        queue.clear();
        current.reset();
        planner.clear();
        for (auto& h : heaters) h.target_c = 0;
    }

    // --- Bytes in ---------------------------------------------------------------------------

    void on_byte(char c) {
        if (silent || booting) return;
        if (o.emergency_parser) scan_emergency(c);
        if (killed) return;
        if (static_cast<int>(rx.size()) >= o.rx_buffer_bytes) {
            ++dropped;  // the ISR drops bytes on a full ring
            return;
        }
        rx.push_back(c);
    }

    // Marlin's emergency parser runs in the RX interrupt, before the byte is stored.
    void scan_emergency(char c) {
        if (c != '\n' && c != '\r') {
            if (ep_line.size() < 40) ep_line.push_back(c);
            return;
        }
        std::string l = trim(ep_line);
        ep_line.clear();
        if (!l.empty() && l[0] == 'N') {
            const auto sp = l.find(' ');
            l = sp == std::string::npos ? "" : l.substr(sp + 1);
        }
        if (const auto star = l.find('*'); star != std::string::npos) l = l.substr(0, star);
        emergency(trim(l));
    }

    // Returns true when `cmd` was an emergency command (acted on).
    bool emergency(const std::string& cmd) {
        const std::string w = marlin::command_word(cmd);
        if (w == "M108") {
            heat_wait_broken = true;
        } else if (w == "M112") {
            if (!killed) kill("");
        } else if (w == "M410") {
            planner.clear();
        } else {
            return false;
        }
        return true;
    }

    // --- Reading lines (queue.cpp) -------------------------------------------------------

    void get_serial_commands() {
        while (static_cast<int>(queue.size()) < o.command_buffer_lines && !rx.empty() && !killed &&
               !booting) {
            const char c = rx.front();
            rx.pop_front();
            if (c == '\n' || c == '\r') {
                in_comment = false;
                if (!partial.empty()) {
                    std::string l;
                    l.swap(partial);
                    on_line(l);
                }
                continue;
            }
            if (c == ';') in_comment = true;
            if (in_comment) continue;
            if (partial.size() < marlin::max_framed_bytes) partial.push_back(c);  // rest is lost
        }
    }

    void on_line(std::string l) {
        while (!l.empty() && l.front() == ' ') l.erase(l.begin());
        std::optional<std::int64_t> n;
        if (!l.empty() && l[0] == 'N') {
            try {
                n = std::stoll(l.substr(1));
            } catch (const std::exception&) {
            }
        }
        if (n) {
            if (drop.erase(*n)) return;
            if (corrupt.erase(*n)) {
                const auto pos = l.find(' ') + 2;
                if (pos < l.size() && l[pos] != '*') l[pos] = l[pos] == '7' ? '3' : '7';
            }
            if (reset_at && *reset_at == *n) {
                reset_at.reset();
                reboot(true, now());
                return;
            }
            if (duplicate.erase(*n)) process_line(l);
        }
        process_line(l);
    }

    void line_error(const std::string& what) {
        emit("Error:" + what + ", Last Line: " + std::to_string(last_n));
        // flush_and_request_resend: drop the RX backlog, ask again.
        rx.clear();
        partial.clear();
        std::int64_t want = last_n + 1;
        if (garble_resend) {
            garble_resend = false;
            want += 100000;
        }
        emit("Resend: " + std::to_string(want));
        if (o.resend_ok) emit("ok");
    }

    void process_line(const std::string& l) {
        if (l.empty() || l[0] != 'N') {
            if (!o.emergency_parser && emergency(l)) return;
            queue.emplace_back(trim(l), std::nullopt);
            return;
        }
        const std::int64_t n = std::stoll(l.substr(1));
        const auto star = l.rfind('*');
        if (star == std::string::npos) return line_error("No Checksum with line number");
        const bool m110 = l.find("M110") != std::string::npos;
        if (!m110 && n != last_n + 1) return line_error("Line Number is not Last Line Number+1");
        int cs = -1;
        try {
            cs = std::stoi(l.substr(star + 1));
        } catch (const std::exception&) {
        }
        if (cs != marlin::checksum(std::string_view(l).substr(0, star)))
            return line_error("checksum mismatch");
        const auto sp = l.find(' ');
        std::string cmd = sp < star ? trim(l.substr(sp + 1, star - sp - 1)) : "";
        last_n = n;
        if (m110) {
            if (auto j = param(cmd, 'N')) last_n = static_cast<std::int64_t>(*j);
        }
        if (!o.emergency_parser && emergency(cmd)) return;
        queue.emplace_back(cmd, n);
    }

    // --- Time: planner and heaters ----------------------------------------------------

    void advance(double t) {
        while (!planner.empty() && planner.front().end_s <= t) planner.pop_front();
        const double dt = t - thermal_t;
        thermal_t = t;
        for (int i = 0; i < 3; ++i) {
            Heater& h = heaters[static_cast<std::size_t>(i)];
            const double goal = h.target_c > 0 ? h.target_c : o.ambient_c;
            const double tau = i == 2 ? o.bed_tau_s : o.hotend_tau_s;
            h.temp_c += (goal - h.temp_c) * (1.0 - std::exp(-dt / tau));
        }
    }

    std::string temperature_line() const {
        char buf[200];
        const Heater& a = heaters[static_cast<std::size_t>(tool)];
        std::snprintf(buf, sizeof buf,
                      "T:%.2f /%.2f B:%.2f /%.2f T0:%.2f /%.2f T1:%.2f /%.2f @:0 B@:0 @0:0 @1:0",
                      a.temp_c, a.target_c, heaters[2].temp_c, heaters[2].target_c,
                      heaters[0].temp_c, heaters[0].target_c, heaters[1].temp_c,
                      heaters[1].target_c);
        return buf;
    }

    // --- Executing commands ----------------------------------------------------------

    void finish(Exec& e, double t) {
        executed.push_back({t, e.line, e.text, e.move_start_s, e.move_end_s,
                            executed_dropped + executed.size()});
        if (o.max_log > 0 && executed.size() > o.max_log) {
            executed.pop_front();
            ++executed_dropped;
        }
        cv.notify_all();
        if (e.line && delay.count(*e.line)) {
            e.wait = Wait::ok_delay;
            e.until_s = t + delay[*e.line];
            delay.erase(*e.line);
            return;
        }
        send_ok(e);
    }

    void send_ok(Exec& e) {
        e.wait = Wait::none;
        if (!e.ok_pending) return;
        e.ok_pending = false;
        if (e.line && swallow.erase(*e.line)) return;
        if (o.advanced_ok) {
            emit("ok" + (e.line ? " N" + std::to_string(*e.line) : std::string()) + " P" +
                 std::to_string(o.planner_blocks - static_cast<int>(planner.size())) + " B" +
                 std::to_string(o.command_buffer_lines - static_cast<int>(queue.size())));
        } else {
            emit("ok");
        }
    }

    void pin_event(const std::string& text, double t) {
        pins.push_back({t, text, static_cast<int>(planner.size()), last_move_end});
        if (o.max_log > 0 && pins.size() > o.max_log) pins.pop_front();
    }

    void begin(Exec& e, double t) {
        const std::string& w = e.word;
        const std::string& c = e.text;
        e.started_s = e.last_busy_s = e.last_report_s = t;
        if (w == "G0" || w == "G1") {
            e.wait = Wait::planner_slot;
        } else if (w == "M400" || w == "M3" || w == "M4" || w == "M5") {
            e.wait = Wait::planner_empty;
        } else if (w == "G4") {
            e.wait = Wait::planner_empty;
            e.dwell_s = param(c, 'S').value_or(param(c, 'P').value_or(0) / 1000.0);
        } else if (w == "M104" || w == "M109" || w == "M140" || w == "M190") {
            const bool bed = w == "M140" || w == "M190";
            const int h = bed ? 2 : static_cast<int>(param(c, 'T').value_or(tool));
            if (h < 0 || h > 2) {
                emit("echo:Invalid extruder " + std::to_string(h));
                return finish(e, t);
            }
            const auto s = param(c, 'S');
            const auto r = param(c, 'R');
            Heater& heater = heaters[static_cast<std::size_t>(h)];
            heater.target_c = s.value_or(r.value_or(0));
            const bool wait = w == "M109" || w == "M190";
            // S waits only when heating, R also when cooling (M109.md).
            if (wait && (r || heater.temp_c < heater.target_c - o.temp_window_c)) {
                e.wait = Wait::heating;
                e.heater = h;
                e.wait_cooling = r.has_value();
                heat_wait_broken = false;
                return;
            }
            finish(e, t);
        } else if (w == "M105") {
            emit("ok " + temperature_line());
            e.ok_pending = false;
            finish(e, t);
        } else if (w == "M155") {
            autoreport_s = param(c, 'S').value_or(0);
            last_autoreport = t;
            finish(e, t);
        } else if (w == "M113") {
            keepalive_s = param(c, 'S').value_or(keepalive_s);
            finish(e, t);
        } else if (w == "M115") {
            emit("FIRMWARE_NAME:Marlin 1.1.9 (Github) SOURCE_CODE_URL:https://github.com/"
                 "MarlinFirmware/Marlin PROTOCOL_VERSION:1.0 MACHINE_TYPE:3D Printer "
                 "EXTRUDER_COUNT:2 UUID:cede2a2f-41a2-4748-9b12-c55c62f367ff");
            for (const char* cap : {"SERIAL_XON_XOFF:0", "EEPROM:1", "VOLUMETRIC:1",
                                    "AUTOREPORT_TEMP:1", "PROGRESS:0", "PRINT_JOB:1", "AUTOLEVEL:0",
                                    "Z_PROBE:0", "LEVELING_DATA:0", "BUILD_PERCENT:0",
                                    "SOFTWARE_POWER:0", "TOGGLE_LIGHTS:0",
                                    "CASE_LIGHT_BRIGHTNESS:0"})
                emit(std::string("Cap:") + cap);
            emit(std::string("Cap:EMERGENCY_PARSER:") + (o.emergency_parser ? "1" : "0"));
            emit("Cap:AUTOREPORT_SD_STATUS:0");
            emit("Cap:THERMAL_PROTECTION:1");
            finish(e, t);
        } else if (w == "M114") {
            char buf[100];
            std::snprintf(buf, sizeof buf, "X:0.00 Y:0.00 Z:0.00 E:%.2f Count X:0 Y:0 Z:0",
                          e_pos[static_cast<std::size_t>(tool)]);
            emit(buf);
            finish(e, t);
        } else if (w == "M42" || w == "M280") {
            pin_event(c, t);  // no planner sync: acts when dequeued (M42.cpp, M280.cpp)
            finish(e, t);
        } else if (w == "T0" || w == "T1") {
            tool = w == "T1" ? 1 : 0;
            emit("echo:Home XYZ first");  // the GT2560 here has no axes to home
            emit("echo:Active Extruder: " + std::to_string(tool));
            finish(e, t);
        } else if (w == "M302") {
            // M302 P1 allows cold extrusion, P0 forbids it; S sets the minimum temperature.
            if (auto v = param(c, 'S')) min_extrude_c = *v;
            if (auto v = param(c, 'P')) cold_extrusion_allowed = *v != 0;
            finish(e, t);
        } else if (w == "M82" || w == "M83") {
            relative_e = w == "M83";
            finish(e, t);
        } else if (w == "G92") {
            if (auto v = param(c, 'E')) e_pos[static_cast<std::size_t>(tool)] = *v;
            finish(e, t);
        } else if (w == "M110") {
            if (!e.line) {
                if (auto j = param(c, 'N')) last_n = static_cast<std::int64_t>(*j);
            }
            finish(e, t);
        } else if (w == "M108" || w == "M112" || w == "M410" || w == "M999" || w == "G28" ||
                   w == "G90" || w == "G91" || w == "M17" || w == "M18" ||
                   w == "M84" || w == "M117" || w == "M106" || w == "M107") {
            finish(e, t);
        } else {
            emit("echo:Unknown command: \"" + c + "\"");
            finish(e, t);
        }
    }

    void queue_move(Exec& e, double t) {
        const double f = param(e.text, 'F').value_or(feed_mm_min);
        feed_mm_min = f;
        double de = 0;
        if (auto v = param(e.text, 'E')) {
            double& pos = e_pos[static_cast<std::size_t>(tool)];
            de = relative_e ? *v : *v - pos;
            pos = relative_e ? pos + *v : *v;
        }
        // PREVENT_COLD_EXTRUSION: the E part of a move is dropped, once per move, with a message.
        if (de != 0 && !cold_extrusion_allowed &&
            heaters[static_cast<std::size_t>(tool)].temp_c < min_extrude_c) {
            emit("echo: cold extrusion prevented");
            de = 0;
            ++cold_refusals;
        }
        const double duration = f > 0 ? std::abs(de) / (f / 60.0) : 0;
        const double start = std::max(t, planner.empty() ? t : planner.back().end_s);
        planner.push_back({start + duration});
        last_move_end = start + duration;
        e.move_start_s = start;
        e.move_end_s = start + duration;
    }

    // Returns true when the current command is complete and its ok is out.
    bool progress(Exec& e, double t) {
        switch (e.wait) {
            case Wait::none: return true;
            case Wait::planner_slot:
                if (static_cast<int>(planner.size()) >= o.planner_blocks) break;
                queue_move(e, t);
                finish(e, t);
                return e.wait == Wait::none;
            case Wait::planner_empty:
                if (!planner.empty()) break;
                if (e.word == "G4") {
                    e.wait = Wait::dwell;
                    e.until_s = t + e.dwell_s;
                    return progress(e, t);
                }
                if (e.word != "M400") pin_event(e.text, t);  // M3/M5 act after the sync
                finish(e, t);
                return e.wait == Wait::none;
            case Wait::dwell:
                if (t < e.until_s) break;
                finish(e, t);
                return e.wait == Wait::none;
            case Wait::heating: {
                const Heater& h = heaters[static_cast<std::size_t>(e.heater)];
                if (heat_wait_broken) {
                    heat_wait_broken = false;
                    finish(e, t);
                    return e.wait == Wait::none;
                }
                const bool in_window = std::abs(h.temp_c - h.target_c) <= o.temp_window_c;
                if (in_window && e.in_window_since < 0) e.in_window_since = t;
                if (!in_window) e.in_window_since = -1;
                if (e.in_window_since >= 0 && t - e.in_window_since >= o.residency_s) {
                    finish(e, t);
                    return e.wait == Wait::none;
                }
                if (t - e.last_report_s >= 1.0) {  // heat-up progress every second
                    e.last_report_s = t;
                    const std::string w =
                        e.in_window_since < 0
                            ? " W:?"
                            : " W:" + std::to_string(static_cast<int>(
                                          o.residency_s - (t - e.in_window_since)));
                    emit(temperature_line() + w);
                }
                break;
            }
            case Wait::ok_delay:
                if (t < e.until_s) return false;
                send_ok(e);
                return true;
        }
        if (e.wait != Wait::ok_delay && t - e.last_busy_s >= keepalive_s) {
            e.last_busy_s = t;
            emit("echo:busy: processing");
        }
        return false;
    }

    void step(double t) {
        if (booting) {
            if (t < boot_until) return;
            booting = false;
            rx.clear();  // input during the bootloader window is lost
            banner();
        }
        if (killed) return;
        advance(t);
        for (const auto& a : actions) emit("//action:" + a);
        actions.clear();
        if (runaway) {
            const int h = *runaway;
            runaway.reset();
            return kill("Thermal Runaway, system stopped! Heater_ID: " +
                        std::string(h == 2 ? "bed" : std::to_string(h)));
        }
        if (autoreport_s > 0 && t - last_autoreport >= autoreport_s) {
            last_autoreport = t;
            emit(" " + temperature_line());
        }
        for (int guard = 0; guard < 64 && !killed && !booting; ++guard) {
            if (current) {
                if (!progress(*current, t)) return;
                current.reset();
            }
            get_serial_commands();
            if (queue.empty()) return;
            Exec e;
            e.text = queue.front().first;
            e.line = queue.front().second;
            e.word = marlin::command_word(e.text);
            queue.pop_front();
            current = std::move(e);
            begin(*current, t);
        }
    }

    void run() {
        char buf[512];
        while (!stop.load()) {
            int fd;
            {
                std::lock_guard lock(mu);
                fd = unplugged ? -1 : pty.master();
            }
            if (fd < 0) {
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
                continue;
            }
            pollfd p{fd, POLLIN, 0};
            ::poll(&p, 1, 1);
            if (tick(fd, p.revents, buf, sizeof buf))
                std::this_thread::sleep_for(std::chrono::milliseconds(1));  // POLLHUP stays up
        }
    }

    // One pass of the firmware loop; returns true while the port is closed (nobody reading).
    bool tick(int fd, short revents, char* buf, std::size_t size) {
        std::lock_guard lock(mu);
        if (unplugged || pty.master() != fd) return false;
        const double t = now();
        if (!connected && !(revents & POLLHUP)) {
            connected = true;  // the host opened the port: DTR pulses the reset line
            if (o.reset_on_open) reboot(false, t);
        }
        // Bytes the host wrote just before closing still arrive (its last M112, for one).
        if (revents & POLLIN) {
            const ssize_t n = ::read(fd, buf, size);
            for (ssize_t i = 0; i < n; ++i) on_byte(buf[i]);
        }
        if (connected) step(t);
        if (revents & POLLHUP) {
            connected = false;
            return true;
        }
        return false;
    }
};

MockGt2560::MockGt2560(MockGt2560Options options)
    : impl_(std::make_unique<Impl>(std::move(options))) {
    impl_->keepalive_s = impl_->o.keepalive_s;
    for (auto& h : impl_->heaters) h.temp_c = impl_->o.ambient_c;
    impl_->open_pty();
    if (!impl_->o.reset_on_open) impl_->reboot(false, 0);
    impl_->thread = std::thread([this] {
        config::make_thread_time_critical("sim.board");
        impl_->run();
    });
}

MockGt2560::~MockGt2560() {
    impl_->stop = true;
    impl_->thread.join();
    impl_->close_pty();
}

std::string MockGt2560::port_path() const {
    std::lock_guard lock(impl_->mu);
    return impl_->pty.port_path();
}

double MockGt2560::sim_now_s() const { return impl_->now(); }

std::chrono::steady_clock::time_point MockGt2560::wall_at(double sim_s) const {
    return impl_->t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(sim_s / impl_->o.time_scale));
}

void MockGt2560::corrupt_line(std::int64_t k) {
    std::lock_guard lock(impl_->mu);
    impl_->corrupt.insert(k);
}
void MockGt2560::drop_line(std::int64_t k) {
    std::lock_guard lock(impl_->mu);
    impl_->drop.insert(k);
}
void MockGt2560::duplicate_line(std::int64_t k) {
    std::lock_guard lock(impl_->mu);
    impl_->duplicate.insert(k);
}
void MockGt2560::swallow_ok(std::int64_t k) {
    std::lock_guard lock(impl_->mu);
    impl_->swallow.insert(k);
}
void MockGt2560::delay_ok(std::int64_t k, double sim_s) {
    std::lock_guard lock(impl_->mu);
    impl_->delay[k] = sim_s;
}
void MockGt2560::garble_next_resend() {
    std::lock_guard lock(impl_->mu);
    impl_->garble_resend = true;
}
void MockGt2560::reset_at_line(std::int64_t k) {
    std::lock_guard lock(impl_->mu);
    impl_->reset_at = k;
}
void MockGt2560::reset_now() {
    std::lock_guard lock(impl_->mu);
    impl_->reboot(true, impl_->now());
}
void MockGt2560::go_silent(bool silent) {
    std::lock_guard lock(impl_->mu);
    impl_->silent = silent;
}
void MockGt2560::unplug() {
    std::lock_guard lock(impl_->mu);
    impl_->close_pty();
    impl_->unplugged = true;
    impl_->connected = false;
}
void MockGt2560::replug() {
    std::lock_guard lock(impl_->mu);
    if (!impl_->unplugged) return;
    impl_->open_pty();
    impl_->reboot(false, impl_->now());  // power comes back with the cable
}
void MockGt2560::thermal_runaway(int heater) {
    std::lock_guard lock(impl_->mu);
    impl_->runaway = heater;
}
void MockGt2560::send_action(const std::string& action) {
    std::lock_guard lock(impl_->mu);
    impl_->actions.push_back(action);
}

std::vector<ExecutedCommand> MockGt2560::executed() const {
    std::lock_guard lock(impl_->mu);
    return {impl_->executed.begin(), impl_->executed.end()};
}
std::vector<ExecutedCommand> MockGt2560::executed_since(std::size_t first) const {
    std::lock_guard lock(impl_->mu);
    const std::size_t skip = first > impl_->executed_dropped ? first - impl_->executed_dropped : 0;
    if (skip >= impl_->executed.size()) return {};
    return {impl_->executed.begin() + static_cast<std::ptrdiff_t>(skip), impl_->executed.end()};
}
std::size_t MockGt2560::executed_count() const {
    std::lock_guard lock(impl_->mu);
    return impl_->executed_dropped + impl_->executed.size();
}
std::vector<PinEvent> MockGt2560::pin_events() const {
    std::lock_guard lock(impl_->mu);
    return {impl_->pins.begin(), impl_->pins.end()};
}
double MockGt2560::temperature_c(int heater) const {
    std::lock_guard lock(impl_->mu);
    return impl_->heaters.at(static_cast<std::size_t>(heater)).temp_c;
}
double MockGt2560::target_c(int heater) const {
    std::lock_guard lock(impl_->mu);
    return impl_->heaters.at(static_cast<std::size_t>(heater)).target_c;
}
bool MockGt2560::killed() const {
    std::lock_guard lock(impl_->mu);
    return impl_->killed;
}
std::uint64_t MockGt2560::cold_extrusion_refusals() const {
    std::lock_guard lock(impl_->mu);
    return impl_->cold_refusals;
}

std::uint64_t MockGt2560::rx_bytes_dropped() const {
    std::lock_guard lock(impl_->mu);
    return impl_->dropped;
}
bool MockGt2560::wait_for_executed(std::size_t n, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(impl_->mu);
    return impl_->cv.wait_for(lock, timeout, [&] {
        return impl_->executed_dropped + impl_->executed.size() >= n;
    });
}

}  // namespace fibrecell::drivers::sim
