#pragma once
// The simulated devices as processes of their own, like the real ones on a cell: the mock GT2560
// (mock-gt2560, logging every command it runs) and the simulated IRC5 (fibrecell-simcell,
// recording its trajectory). ServiceTest's cell YAML then points fibrecelld's real drivers at
// them (simulation.devices: external).
#include "child_process.hpp"
#include "service_fixture.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <sstream>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <vector>
#include <string>

namespace fibrecell::test {

class ExternalCell {
  public:
    // With `board_control`, board_command() injects the mock board's faults (its stdin);
    // `board_options` are more of mock-gt2560's options.
    ExternalCell(const fs::path& dir, double time_scale, bool board_control = false,
                 const std::vector<std::string>& board_options = {})
        : board_log_(dir / "board.log"), trajectory_(dir / "trajectory.csv"), tty_(dir / "ttyGT2560") {
        const std::string bin = fibrecell::test::binary_path();
        const std::string scale = std::to_string(time_scale);
        std::vector<std::string> board_args{"--link", tty_.string(), "--time-scale", scale,
                                            "--bootloader-s", "0.2", "--hotend-tau-s", "2",
                                            "--residency-s", "0.5", "--log", board_log_.string(),
                                            "--emergency-parser"};  // as the cell's firmware
        board_args.insert(board_args.end(), board_options.begin(), board_options.end());
        if (!board_control) board_args.insert(board_args.begin(), "--daemon");
        board_ = std::make_unique<ChildProcess>(bin + "/tools/mock-gt2560", board_args,
                                                dir / "mock.log", board_control);
        robot_ = std::make_unique<ChildProcess>(
            bin + "/tools/fibrecell-simcell/fibrecell-simcell",
            std::vector<std::string>{"--time-scale", scale, "--trajectory", trajectory_.string()},
            dir / "simcell.log");
    }

    // Waits until both are up and reads the simulated IRC5's ports; false (with the reason
    // reported) when one did not start.
    bool up() {
        if (!board_->wait_for_log("port ", 10s)) {
            ADD_FAILURE() << board_->log();
            return false;
        }
        if (!robot_->wait_for_log("modbus=", 20s)) {
            ADD_FAILURE() << robot_->log();
            return false;
        }
        // "fibrecell-simcell: rws=<port> modbus=<port>"
        const std::string banner = robot_->log();
        const auto at = banner.find("rws=");
        if (at == std::string::npos ||
            std::sscanf(banner.c_str() + at, "rws=%d modbus=%d", &rws_port_, &modbus_port_) != 2) {
            ADD_FAILURE() << banner;
            return false;
        }
        return true;
    }

    // The cell YAML of ServiceTest::write_config, changed to use these devices; `extra` is added.
    std::string cell_yaml(const std::string& config_text, const std::string& extra = "") const {
        std::string text = config_text;
        const auto replace = [&](const std::string& from, const std::string& to) {
            const auto pos = text.find(from);
            if (pos == std::string::npos) {
                ADD_FAILURE() << "no '" << from << "' in the cell YAML";
                return;
            }
            text.replace(pos, from.size(), to);
        };
        replace("robot_io: {stable_reads: 1}",
                "robot_io: {stable_reads: 1, port: " + std::to_string(modbus_port_) + "}");
        replace("residency_s: 0.5}", "residency_s: 0.5, devices: external}");
        replace("extruder: {", "extruder: {link: {port: " + tty_.string() + "}, ");
        return text + "rws: {port: " + std::to_string(rws_port_) + "}\n" + extra;
    }

    // A fault of the mock board ("reset", "unplug", "replug", ...: mock-gt2560's stdin
    // commands); waits until the board has done it.
    bool board_command(const std::string& command) {
        const std::string done = "done " + command.substr(0, command.find(' '));
        const auto count = [&] {
            const std::string log = board_->log();
            std::size_t n = 0;
            for (auto at = log.find(done); at != std::string::npos; at = log.find(done, at + 1)) ++n;
            return n;
        };
        const std::size_t before = count();
        return board_->send_line(command) && eventually([&] { return count() > before; }, 10s);
    }

    // The mock board's own heater targets [C] (its `heaters` command), T0 and T1; nullopt when
    // it did not answer.
    std::optional<std::pair<double, double>> board_heater_targets() {
        if (!board_command("heaters")) return std::nullopt;
        const std::string log = board_->log();
        const auto at = log.rfind("heaters T0 ");
        std::pair<double, double> t;
        if (at == std::string::npos ||
            std::sscanf(log.c_str() + at, "heaters T0 %lf T1 %lf", &t.first, &t.second) != 2)
            return std::nullopt;
        return t;
    }

    // The simulated IRC5 gone (its process killed): the robot's links fall.
    void kill_robot() { robot_->kill_now(); }

    const fs::path& board_log() const { return board_log_; }
    // Filament the board ran per tool [mm], from its log ("<t>\t<command>" lines): the E of every
    // relative G1 E, charged to the tool selected last (T0 PLA, T1 fibre).
    std::array<double, 2> board_fed() const {
        std::array<double, 2> mm{};
        std::istringstream in(read_file(board_log_));
        std::string line;
        std::size_t tool = 0;
        while (std::getline(in, line)) {
            const std::string cmd = line.substr(line.find('\t') + 1);
            if (cmd == "T0" || cmd == "T1") tool = cmd == "T1" ? 1 : 0;
            if (cmd.rfind("G1 E", 0) == 0) mm[tool] += std::stod(cmd.substr(4));
        }
        return mm;
    }
    const fs::path& trajectory() const { return trajectory_; }
    // What the simulated IRC5 printed (its task's TPWrite lines among them).
    std::string robot_log() const { return robot_->log(); }

  private:
    fs::path board_log_, trajectory_, tty_;
    std::unique_ptr<ChildProcess> board_, robot_;
    int rws_port_ = 0, modbus_port_ = 0;
};

}  // namespace fibrecell::test
