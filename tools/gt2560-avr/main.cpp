// gt2560-avr: a GT2560 Rev A running real ATmega2560 firmware (stock Marlin built by the user, or
// tests/firmware) in simavr, at real time, its UART0 on a pseudo-terminal (docs/board-simulator.md).
// It prints "port <path>" once the firmware runs; a host opens that path like /dev/ttyUSB0.
// Control commands on stdin, one per line, each answered on stdout:
//   status                                   -> "status {json}": pins, steps, temperatures, faults
//   fault to-board|from-board drop|flip|line P   byte drop / bit flip / one line in 1/P corrupted
//   fault off                                -> no faults either way
//   pause SECONDS | unplug | replug | reset | quit
// With --daemon stdin is ignored and it runs until SIGTERM or SIGINT.
#include "daemon/cell/cell_config.hpp"
#include "drivers/sim/avr/avr_board.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <sstream>
#include <thread>

namespace avr = fibrecell::drivers::sim::avr;

namespace {

std::atomic<bool> stop_requested{false};
extern "C" void on_stop_signal(int) { stop_requested = true; }

// One control line; false when it is not understood.
bool control(avr::AvrBoard& board, const std::string& line, avr::WireFaultRates (&rates)[2]) {
    std::istringstream in(line);
    std::string cmd;
    in >> cmd;
    if (cmd == "status") {
        std::cout << "status " << board.status_json() << std::endl;
        return true;
    }
    if (cmd == "fault") {
        std::string side, kind;
        double p = 0;
        in >> side;
        if (side == "off") {
            for (auto s : {avr::WireSide::to_board, avr::WireSide::from_board}) board.set_wire_faults(s, {});
            rates[0] = rates[1] = {};
        } else {
            if (!(in >> kind >> p) || p < 0 || p > 1 || (side != "to-board" && side != "from-board"))
                return false;
            const int i = side == "to-board" ? 0 : 1;
            if (kind == "drop") rates[i].drop_byte = p;
            else if (kind == "flip") rates[i].flip_byte = p;
            else if (kind == "line") rates[i].corrupt_line = p;
            else return false;
            board.set_wire_faults(i == 0 ? avr::WireSide::to_board : avr::WireSide::from_board, rates[i]);
        }
    } else if (cmd == "pause") {
        double s = 0;
        if (!(in >> s) || s < 0 || s > 3600) return false;
        board.pause(s);
    } else if (cmd == "unplug") board.unplug();
    else if (cmd == "replug") board.replug();
    else if (cmd == "reset") board.reset();
    else return false;
    std::cout << "done " << cmd << std::endl;
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    avr::AvrBoardOptions o;
    std::string cell_path;
    bool daemon = false;
    CLI::App app{"GT2560 running real AVR firmware (simavr), on a pseudo-terminal"};
    app.add_option("firmware", o.firmware, "ATmega2560 firmware: .elf or .hex")->required();
    app.add_option("--link", o.link_path, "symlink to create for the port (stable across replug)");
    app.add_option("--cell", cell_path, "cell YAML whose simulation: section sets the hotends' "
                                        "heater power, loss, heat capacity and ambient");
    app.add_option("--steps-per-mm", o.pins.steps_per_mm, "E steps/mm of the firmware build")
        ->check(CLI::PositiveNumber);
    app.add_flag("--invert-e-dir", o.pins.invert_e_dir, "dir low is forward (INVERT_E0_DIR)");
    app.add_option("--edge-log", o.edge_log, "write every pin edge to this file");
    app.add_option("--seed", o.fault_seed, "seed of the wire faults");
    app.add_flag("--daemon", daemon, "ignore stdin; run until SIGTERM or SIGINT");
    CLI11_PARSE(app, argc, argv);

    try {
        if (!cell_path.empty()) {
            const auto sim = fibrecell::daemon::load_cell_config(cell_path).simulation;
            o.hotend = {.power_w = sim.heater_power_w, .loss_w_per_k = sim.heater_loss_w_per_k,
                        .fan_loss_w_per_k = sim.heater_fan_loss_w_per_k,
                        .heat_capacity_j_per_k = sim.heat_capacity_j_per_k, .ambient_c = sim.ambient_c};
        }
        avr::AvrBoard board(o);
        std::cout << "port " << board.port_path() << std::endl;
        if (daemon) {
            std::signal(SIGTERM, on_stop_signal);
            std::signal(SIGINT, on_stop_signal);
            while (!stop_requested) std::this_thread::sleep_for(std::chrono::milliseconds(20));
            return 0;
        }
        avr::WireFaultRates rates[2];
        std::string line;
        while (std::getline(std::cin, line)) {
            if (line == "quit") break;
            if (line.empty()) continue;
            if (!control(board, line, rates))
                std::cout << "error unknown or incomplete control command '" << line << "'" << std::endl;
        }
        return 0;
    } catch (const std::exception& e) {
        std::cerr << e.what() << '\n';
        return 1;
    }
}
