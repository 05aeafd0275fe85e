#include "daemon/devices/cell_devices.hpp"

#include "drivers/sim/cell/sim_cell.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include <filesystem>
#include <thread>

namespace fibrecell::daemon::devices {

namespace abb = drivers::abb;
using nlohmann::json;

namespace {

std::unique_ptr<drivers::sim::MockGt2560> make_mock_board(const CellConfig& cell,
                                                         const std::filesystem::path& link) {
    drivers::sim::MockGt2560Options o;
    o.time_scale = cell.simulation.time_scale;
    o.hotend_tau_s = cell.simulation.hotend_tau_s;
    o.residency_s = cell.simulation.residency_s;
    o.bootloader_s = 0.5;
    o.emergency_parser = cell.simulation.board_emergency_parser;
    o.link_path = link.string();
    o.max_log = 10'000;  // observed by nobody in the service: bounded so that job after job
                         // does not grow the service's memory
    return std::make_unique<drivers::sim::MockGt2560>(o);
}

std::unique_ptr<drivers::sim::SimCell> make_sim_cell(const CellConfig& cell) {
    drivers::sim::SimCellOptions o;
    o.time_scale = cell.simulation.time_scale;
    o.rws.user = cell.rws.client.user;
    o.rws.password = cell.rws.client.password;
    o.io_map = cell.robot_io.map;
    o.signals = cell.robot.signals;
    o.main_module = resolve_main_module(cell.simulation.main_module);
    o.motion.max_samples = cell.simulation.trajectory_samples;
    o.on_task_log = [](const drivers::sim::TaskLogEntry& e) { spdlog::info("simcell.task {}", e.text); };
    return std::make_unique<drivers::sim::SimCell>(o);
}

void put(json& j, const char* key, const std::optional<double>& v) {
    if (v) j[key] = *v;
}

}  // namespace

CellDevices::CellDevices(const CellConfig& cell) : cell_(cell), extruder_(cell.extruder) {
    drivers::marlin::MarlinLinkConfig board_config = cell.extruder.link;
    abb::rws::RwsClientConfig rws_config = cell.rws.client;
    abb::RobotIoConfig io_config = cell.robot_io;
    if (cell.simulated) time_scale_ = cell.simulation.time_scale;
    if (cell.simulated && !cell.simulation.external_devices) {
        std::filesystem::create_directories(cell.state_dir);
        // With `board: external` the link keeps extruder.link.port: gt2560-avr or a real board.
        if (!cell.simulation.external_board) {
            mock_board_ = make_mock_board(cell, std::filesystem::path(cell.state_dir) / "ttyGT2560-sim");
            board_config.serial.device = mock_board_->port_path();
        }
        sim_cell_ = make_sim_cell(cell);
        rws_config.host = "127.0.0.1";
        rws_config.port = sim_cell_->rws_port();
        io_config.host = "127.0.0.1";
        io_config.port = sim_cell_->modbus_port();
        spdlog::info("cell.simulated time_scale={} board={} rws=127.0.0.1:{} modbus=127.0.0.1:{}",
                     time_scale_, board_config.serial.device, rws_config.port, io_config.port);
    }
    board_.configure(board_config);
    board_.on_temperature([this](const drivers::marlin::TemperatureReport& r) { temperature(r); });
    rws_ = std::make_unique<abb::rws::RwsClient>(rws_config);
    robot_io_ = std::make_unique<abb::RobotIoLink>(io_config);
    robot_io_->on_event([this](const abb::EventCounterChange& c) {
        std::lock_guard lock(mu_);
        if (print_) print_->robot_event(c);
    });
    robot_io_->on_state([this](const abb::RobotIoStateChange& c) {
        if (c.to == abb::RobotIoState::fault) spdlog::error("cell.robot_io_fault {}", c.reason);
        std::lock_guard lock(mu_);
        if (print_) print_->robot_link_state(c);
    });
}

CellDevices::~CellDevices() {
    disconnect();
    robot_io_.reset();
    sim_cell_.reset();
    mock_board_.reset();
}

void CellDevices::connect(std::chrono::milliseconds timeout) {
    if (board_.state() != drivers::DeviceState::active) {
        if (board_.state() == drivers::DeviceState::error) board_.clear();
        if (board_.state() == drivers::DeviceState::unconfigured) board_.configure(cell_.extruder.link);
        {
            std::lock_guard lock(mu_);
            temps_ = {};  // the readings of the board before: its own reports come anew
        }
        try {
            board_.activate();
        } catch (const std::exception& e) {
            throw DeviceError(std::string("extruder board: ") + e.what());
        }
    }
    if (robot_io_->snapshot().state == abb::RobotIoState::stopped) robot_io_->start();
    if (!robot_io_->wait_until_up(timeout)) {
        const auto s = robot_io_->snapshot();
        throw DeviceError("robot I/O: not up within " + std::to_string(timeout.count()) + " ms (" +
                          (s.fault_reason.empty() ? s.last_error : s.fault_reason) + ")");
    }
    end_orphan_run(timeout);
}

// A fibrecelld that died mid-print and was started again within FcMain's heartbeat timeout
// (systemd restarts it in 100 ms) finds the robot still running the old run: the heartbeat came
// back before FcMain missed it. Nobody feeds the board for that run, so the robot would lay the
// rest of the path dry and stop only at the next barrier. It is aborted at once: the robot stops
// where it is, and the job's resume re-enters from its journal, as after a hold. A held run
// (doFcRunning low) is left for the resume to end.
void CellDevices::end_orphan_run(std::chrono::milliseconds timeout) {
    {
        std::lock_guard lock(mu_);
        if (print_) return;
    }
    if (!robot_io_->snapshot().running) return;
    spdlog::warn("cell.orphan_run the robot program runs a print this service did not start "
                 "(a restart before FcMain's heartbeat timeout): aborted");
    robot_io_->set_abort(true);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (robot_io_->snapshot().running && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (robot_io_->snapshot().running)
        spdlog::error("cell.orphan_run the robot program did not end its run on the abort request "
                      "within {} ms (a start aborts it again)", timeout.count());
    robot_io_->set_abort(false);
}

void CellDevices::disconnect() {
    if (robot_io_) robot_io_->stop();
    if (board_.state() == drivers::DeviceState::active) board_.deactivate();
}

print::PrintLinks CellDevices::links() { return {*rws_, *robot_io_, board_, extruder_}; }

void CellDevices::set_print(print::PrintSession* session) {
    std::lock_guard lock(mu_);
    print_ = session;
}

void CellDevices::estop() {
    spdlog::critical("cell.estop M112 and robot abort requested (not a safety function)");
    robot_io_->set_pause(true);
    robot_io_->set_abort(true);
    board_.emergency_stop();
}

void CellDevices::temperature(const drivers::marlin::TemperatureReport& r) {
    const auto pla = r.find("T" + std::to_string(cell_.extruder.pla_tool));
    const auto ccf = r.find("T" + std::to_string(cell_.extruder.ccf_tool));
    {
        std::lock_guard lock(mu_);
        if (pla) temps_.pla_c = pla->actual_c, temps_.pla_target_c = pla->target_c;
        if (ccf) temps_.ccf_c = ccf->actual_c, temps_.ccf_target_c = ccf->target_c;
        if (print_) print_->board_temperature(r);
    }
}

HotendTemps CellDevices::temperatures() const {
    std::lock_guard lock(mu_);
    return temps_;
}

json CellDevices::status() const {
    json board = {{"state", std::string(drivers::to_string(board_.state()))}};
    if (board_.fault() != drivers::marlin::LinkFailure::none)
        board["fault"] = std::string(drivers::marlin::to_string(board_.fault())) + ": " +
                         board_.fault_detail();
    // Readings only from a board that is there: a fallen-out one's last ones are no news.
    if (board_.state() == drivers::DeviceState::active) {
        board["emergency_parser"] = board_.emergency_parser();
        const HotendTemps t = temperatures();
        put(board, "pla_c", t.pla_c);
        put(board, "pla_target_c", t.pla_target_c);
        put(board, "ccf_c", t.ccf_c);
        put(board, "ccf_target_c", t.ccf_target_c);
    }
    const abb::RobotIoSnapshot io = robot_io_->snapshot();
    json robot = {{"io", std::string(abb::to_string(io.state))},
                  {"event", io.event_counter},
                  {"running", io.running},
                  {"heartbeat", io.robot_heartbeat_ok}};
    if (!io.fault_reason.empty()) robot["fault"] = io.fault_reason;
    // The link's worst cases since the service started (docs/robot-io.md, "Timeouts").
    const auto ms = [](double v) { return std::round(v * 10) / 10; };
    robot["worst"] = {{"poll_ms", ms(io.stats.poll_us_max / 1000)},
                      {"heartbeat_gap_ms", ms(io.stats.heartbeat_gap_ms_max)},
                      {"robot_heartbeat_gap_ms", ms(io.stats.robot_heartbeat_gap_ms_max)}};
    return {{"board", board}, {"robot", robot}};
}

}  // namespace fibrecell::daemon::devices
