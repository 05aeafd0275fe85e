// fibrecell-simcell: the simulated cell controller as a program (docs/simcell.md). Serves Robot Web
// Services and the Modbus robot I/O map on loopback, executes FcMain and the chunks the service
// uploads, and runs until SIGINT or SIGTERM. Prints one line when ready:
//   fibrecell-simcell: rws=<port> modbus=<port>
// The RWS user, the Modbus map, the signal names and the arm come from the cell YAML's rws:,
// robot_io: and robot: sections; ports are ephemeral unless given (the YAML's ports are where the
// service connects to a real cell). With --trajectory, the robot's TCP trajectory is written to a
// CSV file (created anew) as it is recorded (drivers/sim/motion/trajectory_csv.hpp).
#include "config/logging.hpp"
#include "config/yaml_section.hpp"
#include "drivers/abb/cell/robot_config.hpp"
#include "drivers/abb/modbus/robot_io_config.hpp"
#include "drivers/abb/rws/rws_config.hpp"
#include "drivers/sim/cell/sim_cell.hpp"
#include "drivers/sim/motion/trajectory_csv.hpp"
#include "default_main_module.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <pthread.h>

namespace sim = fibrecell::drivers::sim;
namespace abb = fibrecell::drivers::abb;

namespace {

// The cell YAML's sections that describe the controller; the rest of the file is the service's.
void apply_cell_config(const std::string& path, sim::SimCellOptions& o) {
    fibrecell::config::Section root = fibrecell::config::Section::load_file(path);
    const abb::rws::RwsLinkConfig rws = abb::rws::load_rws_config(root.section("rws"));
    const abb::RobotIoConfig io = abb::load_robot_io_config(root.section("robot_io"));
    const abb::RobotCellConfig robot = abb::load_robot_config(root.section("robot"));
    o.rws.user = rws.client.user;
    o.rws.password = rws.client.password;
    o.rws.task = rws.client.task;
    o.io_map = io.map;
    o.signals = robot.signals;
    o.motion.variant = robot.variant;
    o.motion.solver = robot.solver;
}

// Writes the cell's recorded trajectory to a new CSV file, adding rows every 100 ms (real time) until stopped,
// then once more. Taking it also keeps the recorder from dropping samples on a long run.
class TrajectoryFile {
  public:
    TrajectoryFile(sim::SimCell& cell, const std::string& path) : cell_(cell), out_(path) {
        if (!out_) throw std::runtime_error(path + ": cannot write the trajectory");
        sim::write_trajectory_csv_header(out_);
        out_.flush();
        thread_ = std::thread([this] {
            while (!stop_) {
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
                drain();
            }
        });
    }
    ~TrajectoryFile() {
        stop_ = true;
        thread_.join();
        drain();
    }
    TrajectoryFile(const TrajectoryFile&) = delete;
    TrajectoryFile& operator=(const TrajectoryFile&) = delete;

  private:
    void drain() {
        const auto samples = cell_.take_trajectory();
        if (samples.empty()) return;
        sim::write_trajectory_csv_rows(out_, samples);
        out_.flush();
    }

    sim::SimCell& cell_;
    std::ofstream out_;
    std::atomic<bool> stop_ = false;
    std::thread thread_;
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Simulated IRC5 cell: RWS and Modbus robot I/O on loopback, executing FcMain"};
    std::string config_path;
    double time_scale = 1;
    int rws_port = 0;
    int modbus_port = 0;
    std::string user;
    std::string password;
    std::string main_module = fibrecell::simcell::default_main_module();
    bool start = false;
    std::string log_level;
    std::string trajectory_path;
    app.add_option("--config", config_path, "cell YAML (rws:, robot_io:, robot: sections)")
        ->check(CLI::ExistingFile);
    app.add_option("--time-scale", time_scale, "simulated seconds per real second")
        ->check(CLI::PositiveNumber);
    app.add_option("--rws-port", rws_port, "RWS port (0: ephemeral)")->check(CLI::Range(0, 65535));
    app.add_option("--modbus-port", modbus_port, "Modbus TCP port (0: ephemeral)")
        ->check(CLI::Range(0, 65535));
    app.add_option("--user", user, "RWS user (default: the config's, else Default User)");
    app.add_option("--password", password, "RWS password (default: the config's, else robotics)");
    app.add_option("--main-module", main_module, "resident main module loaded at start-up")
        ->check(CLI::ExistingFile);
    app.add_flag("--start", start, "start RAPID at start-up (otherwise stopped with PP at main)");
    app.add_option("--log-level", log_level, "trace|debug|info|warn|error|off");
    app.add_option("--trajectory", trajectory_path,
                   "write the TCP trajectory to this CSV file (replaced) as it is recorded");
    CLI11_PARSE(app, argc, argv);
    fibrecell::config::setup_logging(log_level);

    // Block the stop signals in every thread the cell starts; this thread waits for them.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    try {
        sim::SimCellOptions o;
        if (!config_path.empty()) apply_cell_config(config_path, o);
        o.time_scale = time_scale;
        o.rws.port = static_cast<std::uint16_t>(rws_port);
        o.io_port = modbus_port;
        if (!user.empty()) o.rws.user = user;
        if (!password.empty()) o.rws.password = password;
        o.main_module = main_module;
        o.start_main = start;
        o.on_task_log = [](const sim::TaskLogEntry& e) {
            spdlog::info("simcell.task t={:.3f}s {}", e.t_s, e.text);
        };
        sim::SimCell cell(std::move(o));
        std::optional<TrajectoryFile> trajectory;
        if (!trajectory_path.empty()) trajectory.emplace(cell, trajectory_path);
        spdlog::info("simcell.ready rws={} modbus={} time_scale={}", cell.rws_port(),
                     cell.modbus_port(), time_scale);
        std::cout << "fibrecell-simcell: rws=" << cell.rws_port()
                  << " modbus=" << cell.modbus_port() << std::endl;
        int sig = 0;
        sigwait(&stop_signals, &sig);
        spdlog::info("simcell.stopping signal={}", sig);
    } catch (const std::exception& e) {
        std::cerr << "fibrecell-simcell: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
