// The board's serial side: the port and its DTR reset, the boot banner, the emergency parser in
// the RX interrupt, and the line reader with its line-number and checksum rules (Marlin's
// queue.cpp).

#include "drivers/sim/mock_board/board_state.hpp"

#include "drivers/marlin/marlin_line.hpp"

#include <unistd.h>

#include <string>

namespace fibrecell::drivers::sim {

std::optional<double> MockGt2560::Impl::param(const std::string& cmd, char key) {
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

std::string MockGt2560::Impl::trim(std::string s) {
    while (!s.empty() && s.front() == ' ') s.erase(s.begin());
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

void MockGt2560::Impl::open_pty() {
    pty.open();
    unplugged = false;
    connected = false;
}

void MockGt2560::Impl::write_raw(const std::string& bytes) {
    if (pty.master() < 0 || !connected) return;
    std::size_t off = 0;
    while (off < bytes.size()) {
        const ssize_t n = ::write(pty.master(), bytes.data() + off, bytes.size() - off);
        if (n <= 0) return;  // host not reading: a real UART would lose it too
        off += static_cast<std::size_t>(n);
    }
}

void MockGt2560::Impl::emit(const std::string& line) {
    if (silent) return;
    write_raw(line + "\n");
}

// ---- Power and boot -------------------------------------------------------------------

void MockGt2560::Impl::reboot(bool noise, double t) {
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
void MockGt2560::Impl::banner() {
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

void MockGt2560::Impl::kill(const std::string& reason) {
    if (!reason.empty()) emit("Error:" + reason);
    emit("Error:Printer halted. kill() called!");
    killed = true;
    queue.clear();
    current.reset();
    planner.clear();
    for (auto& h : heaters) h.target_c = 0;
}

// ---- Bytes in -------------------------------------------------------------------------

void MockGt2560::Impl::on_byte(char c) {
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
void MockGt2560::Impl::scan_emergency(char c) {
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
bool MockGt2560::Impl::emergency(const std::string& cmd) {
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

// ---- Reading lines (queue.cpp) --------------------------------------------------------

void MockGt2560::Impl::get_serial_commands() {
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

void MockGt2560::Impl::on_line(std::string l) {
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

void MockGt2560::Impl::line_error(const std::string& what) {
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

void MockGt2560::Impl::process_line(const std::string& l) {
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

}  // namespace fibrecell::drivers::sim
