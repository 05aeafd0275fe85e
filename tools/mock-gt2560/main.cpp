// mock-gt2560: the simulated GT2560/Marlin board on a pseudo-terminal, for the simulated cell and
// for manual testing (`picocom`, the daemon). Faults come from stdin, one command per line:
//   corrupt K | drop K | duplicate K | swallow-ok K | delay-ok K SECONDS | garble-resend |
//   reset-at K | reset | silent on|off | unplug | replug | runaway HEATER | action TEXT | quit
// and `heaters`, answered "heaters T0 <target C> T1 <target C>" (the board's own state).
// With --daemon it ignores stdin and runs until SIGTERM/SIGINT; --log appends every executed
// command ("<simulated s>\t<command>") to a file, flushed as it goes, so that a test can read the
// board's log after killing the service that drove it.
#include "drivers/sim/mock_board/mock_gt2560.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_stop_signal(int) { stop_requested = true; }

// Appends the board's executed commands to `path` until `done`.
void write_log(const fibrecell::drivers::sim::MockGt2560& mock, const std::string& path,
               const std::atomic<bool>& done) {
    std::ofstream out(path, std::ios::app);
    std::size_t written = 0;
    for (;;) {
        const bool last = done.load();
        for (const auto& c : mock.executed_since(written)) {
            out << c.t_s << '\t' << c.text << '\n';
            written = c.number + 1;
        }
        out.flush();
        if (last) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

}  // namespace

int main(int argc, char** argv) {
    fibrecell::drivers::sim::MockGt2560Options o;
    o.max_log = 100'000;  // the --log file has them all; memory stays bounded on a long run
    CLI::App app{"Mock GT2560 (Marlin) on a pseudo-terminal"};
    app.add_option("--link", o.link_path, "symlink to create for the port (stable across replug)");
    app.add_option("--time-scale", o.time_scale, "simulated seconds per real second")->check(CLI::PositiveNumber);
    app.add_option("--bootloader-s", o.bootloader_s, "simulated boot delay before 'start'");
    app.add_flag("!--no-resend-ok", o.resend_ok, "no ok after Resend (older Marlin)");
    app.add_flag("--emergency-parser", o.emergency_parser,
                 "M108/M112/M410 act as they arrive (a build with EMERGENCY_PARSER; stock 1.1.9: only when read)");
    app.add_flag("!--no-reset-on-open", o.reset_on_open,
                 "opening the port does not reboot the board (auto-reset disabled, or no DTR)");
    app.add_flag("--advanced-ok", o.advanced_ok, "ok N<line> P<planner> B<buffer>");
    app.add_option("--hotend-tau-s", o.hotend_tau_s, "hotend time constant (simulated s)");
    app.add_option("--residency-s", o.residency_s, "M109 residency (simulated s)");
    std::string log_path;
    bool daemon = false;
    app.add_option("--log", log_path, "append every executed command to this file");
    app.add_flag("--daemon", daemon, "ignore stdin; run until SIGTERM or SIGINT");
    CLI11_PARSE(app, argc, argv);

    fibrecell::drivers::sim::MockGt2560 mock(o);
    std::atomic<bool> done{false};
    std::thread logger;
    if (!log_path.empty()) logger = std::thread([&] { write_log(mock, log_path, done); });
    std::cout << "port " << mock.port_path() << std::endl;
    if (daemon) {
        std::signal(SIGTERM, on_stop_signal);
        std::signal(SIGINT, on_stop_signal);
        while (!stop_requested) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        done = true;
        if (logger.joinable()) logger.join();
        return 0;
    }
    std::string line;
    while (std::getline(std::cin, line)) {
        std::istringstream in(line);
        std::string cmd;
        in >> cmd;
        std::int64_t k = 0;
        double s = 0;
        if (cmd == "corrupt" && in >> k) mock.corrupt_line(k);
        else if (cmd == "drop" && in >> k) mock.drop_line(k);
        else if (cmd == "duplicate" && in >> k) mock.duplicate_line(k);
        else if (cmd == "swallow-ok" && in >> k) mock.swallow_ok(k);
        else if (cmd == "delay-ok" && in >> k >> s) mock.delay_ok(k, s);
        else if (cmd == "garble-resend") mock.garble_next_resend();
        else if (cmd == "reset-at" && in >> k) mock.reset_at_line(k);
        else if (cmd == "reset") mock.reset_now();
        else if (cmd == "silent") { std::string on; in >> on; mock.go_silent(on != "off"); }
        else if (cmd == "unplug") mock.unplug();
        else if (cmd == "replug") mock.replug();
        else if (cmd == "runaway" && in >> k) mock.thermal_runaway(static_cast<int>(k));
        else if (cmd == "action") { std::string rest; std::getline(in >> std::ws, rest); mock.send_action(rest); }
        else if (cmd == "heaters") {  // the board's own targets, for tests that check them
            std::cout << "heaters T0 " << mock.target_c(0) << " T1 " << mock.target_c(1) << std::endl;
        } else if (cmd == "quit") break;
        else if (!cmd.empty()) { std::cerr << "mock-gt2560: unknown or incomplete control command '" << line << "'\n"; continue; }
        std::cout << "done " << cmd << std::endl;
    }
    done = true;
    if (logger.joinable()) logger.join();
    return 0;
}
