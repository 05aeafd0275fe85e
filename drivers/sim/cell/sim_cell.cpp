#include "drivers/sim/cell/sim_cell.hpp"

#include "drivers/abb/rapid/names.hpp"

#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace fibrecell::drivers::sim {


namespace {

// "HOME:/fibrecell/job/FcChunk0001.mod" -> "fibrecell/job/FcChunk0001.mod"; nothing for a path
// on another device.
std::optional<std::string> home_relative(const std::string& rapid_path) {
    constexpr std::string_view device = "HOME:";
    if (rapid_path.size() < device.size() ||
        !abb::rapid::same_name(std::string_view(rapid_path).substr(0, device.size()), device))
        return std::nullopt;
    std::string rest = rapid_path.substr(device.size());
    while (!rest.empty() && rest.front() == '/') rest.erase(rest.begin());
    return rest;
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw std::runtime_error("simcell: cannot read the main module " + path.string());
    return text.str();
}

}  // namespace

SimCell::SimCell(SimCellOptions options)
    : options_(std::move(options)),
      clock_(options_.time_scale),
      log_(std::make_unique<TaskLog>(options_.on_task_log)),
      motion_(std::make_unique<MotionSimulator>(clock_, options_.motion)),
      signals_(options_.signals, options_.robot_heartbeat_filter) {
    try {
        SimControllerOptions c;
        c.build.known_signals = signals_.names();
        c.time_scale = options_.time_scale;
        controller_ = std::make_shared<SimController>(std::move(c));

        TaskIo io;
        io.read_signal = [this](const std::string& s) { return signals_.read(s); };
        io.write_signal = [this](const std::string& s, double v) { signals_.write(s, v); };
        io.read_file = [this](const std::string& path) -> std::optional<std::string> {
            const std::optional<std::string> rel = home_relative(path);
            if (!rel) return std::nullopt;
            return controller_->read_file(*rel);
        };
        io.log = [this](const std::string& text) {
            log_->add({clock_.now_s(), std::chrono::steady_clock::now(), text});
        };
        io.known_signals = signals_.names();
        task_ = std::make_unique<RapidTask>(clock_, *motion_, std::move(io));
        controller_->attach(task_.get());

        // The robot heartbeat comes from FcMain (doFcHeartbeat), not from the coupler's timer.
        coupler_ = std::make_unique<RobotIoServer>(
            options_.io_map,
            RobotIoServerOptions{.bind_address = options_.io_address,
                                      .port = options_.io_port,
                                      .robot_heartbeat_period = std::chrono::milliseconds(0)});
        signals_.attach(*coupler_);
        signals_.on_input([this](const std::string& s, double v) { task_->signal_changed(s, v); });
        coupler_->on_commands(
            [this](const ServiceCommands& cmds) { signals_.commands_changed(cmds); });

        load_main_module();
        rws_ = std::make_unique<rws::RwsServer>(controller_, options_.rws);
    } catch (...) {
        shutdown();
        throw;
    }
}

SimCell::~SimCell() {
    shutdown();
}

void SimCell::shutdown() noexcept {
    if (rws_) rws_->stop();
    signals_.detach();  // no I/O forwarded either way from here on
    if (controller_) controller_->attach(nullptr);
    task_.reset();  // joins the task thread
    coupler_.reset();
    rws_.reset();
    motion_.reset();
}

void SimCell::load_main_module() {
    if (options_.main_module.empty()) return;
    const std::string& home = options_.main_module_home_path;
    controller_->write_file(home, read_text(options_.main_module));
    try {
        controller_->load_module(home, true);
        controller_->reset_pp();
        if (options_.start_main) controller_->start({});
    } catch (const rws::BackendError& e) {
        std::string why = e.what();
        for (const rws::BuildError& b : controller_->build_log()) why += "\n  " + rws::format(b);
        throw std::runtime_error("simcell: the main module " + options_.main_module.string() +
                                 " does not load: " + why);
    }
}

std::uint16_t SimCell::rws_port() const {
    return rws_->port();
}
int SimCell::modbus_port() const {
    return coupler_->port();
}

TaskStatus SimCell::task_status() const {
    return controller_->task_status();
}

void SimCell::drop_modbus_link(std::chrono::milliseconds d) {
    coupler_->refuse_connections_for(d);
    coupler_->drop_connections();
}

void SimCell::stop_with_error(const std::string& text) {
    controller_->stop_with_error(text);
    log_->add({clock_.now_s(), std::chrono::steady_clock::now(), "controller error: " + text});
}

void SimCell::motors_off() {
    controller_->set_controller_state(rws::ControllerState::motoroff);
    motion_->motors_off("motors off");
    controller_->stop();
    log_->add({clock_.now_s(), std::chrono::steady_clock::now(), "motors off"});
}

void SimCell::motors_on() {
    motion_->motors_on();
    controller_->set_controller_state(rws::ControllerState::motoron);
}

}  // namespace fibrecell::drivers::sim
