// mock-gt2560: the simulated GT2560/Marlin board on a pseudo-terminal, for the simulated cell and
// for manual testing (`picocom`, the daemon). Faults come from stdin, one command per line:
//   corrupt K | drop K | duplicate K | swallow-ok K | delay-ok K SECONDS | garble-resend |
//   reset-at K | reset | silent on|off | unplug | replug | runaway HEATER | action TEXT | quit
#include "drivers/sim/mock_gt2560.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <sstream>

int main(int argc, char** argv) {
    fibrecell::drivers::sim::MockGt2560Options o;
    CLI::App app{"Mock GT2560 (Marlin) on a pseudo-terminal"};
    app.add_option("--link", o.link_path, "symlink to create for the port (stable across replug)");
    app.add_option("--time-scale", o.time_scale, "simulated seconds per real second")->check(CLI::PositiveNumber);
    app.add_option("--bootloader-s", o.bootloader_s, "simulated boot delay before 'start'");
    app.add_flag("!--no-resend-ok", o.resend_ok, "no ok after Resend (older Marlin)");
    app.add_flag("!--no-emergency-parser", o.emergency_parser, "M108/M112/M410 only when read");
    app.add_flag("--advanced-ok", o.advanced_ok, "ok N<line> P<planner> B<buffer>");
    CLI11_PARSE(app, argc, argv);

    fibrecell::drivers::sim::MockGt2560 mock(o);
    std::cout << "port " << mock.port_path() << std::endl;
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
        else if (cmd == "quit") break;
        else if (!cmd.empty()) { std::cerr << "mock-gt2560: unknown or incomplete control command '" << line << "'\n"; continue; }
        std::cout << "done " << cmd << std::endl;
    }
    return 0;
}
