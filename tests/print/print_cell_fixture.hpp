#pragma once
// A whole simulated cell for end-to-end print tests, every driver real: the simulated IRC5
// (RAPID task executing the real FcMain.mod and the job's chunks, motion, RWS with digest auth,
// the Modbus coupler) on loopback, the mock GT2560 on a pseudo-terminal, and the service's links
// to them (RwsClient, RobotIoLink, MarlinLink, ExtruderController) driving a PrintSession. The
// expected board log is rebuilt independently from the program and a second ExtruderController.
#include "daemon/print/print_session.hpp"
#include "drivers/abb/rapid/rapid_writer.hpp"
#include "drivers/sim/cell/sim_cell.hpp"
#include "drivers/sim/mock_gt2560.hpp"
#include "drivers/sim/motion/trajectory_analysis.hpp"
#include "../sync/metered_pieces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <numbers>
#include <thread>

namespace fibrecell::test {

using namespace std::chrono_literals;
namespace abb = drivers::abb;
using daemon::print::PrintOptions;
using daemon::print::PrintPhase;
using daemon::print::PrintSession;
using drivers::abb::EventKind;

// Simulated seconds per real second. Positions are checked at a lower scale: every real
// millisecond of the service's latency moves the simulated robot `scale` times as far.
constexpr double print_time_scale = 20;
constexpr double pla_speed = 12, ccf_speed = 5;

template <class Pred>
bool eventually(Pred pred, std::chrono::milliseconds timeout = 20'000ms) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
        if (pred()) return true;
        std::this_thread::sleep_for(2ms);
    }
    return pred();
}

inline planner::ToolpathLayer pla_square(int index, double z) {
    planner::ToolpathLayer pla{.index = index, .z = z, .head = planner::Head::pla, .thickness = 0.8};
    pla.paths.push_back(
        {planner::PathRole::perimeter, true, {{140, 140}, {160, 140}, {160, 160}, {140, 160}}});
    return pla;
}

// `count` straight fibre paths of `length` mm along x, 10 mm apart.
inline planner::ToolpathLayer fibre_lines(int index, double z, int count, int length = 100) {
    planner::ToolpathLayer ccf{.index = index, .z = z, .head = planner::Head::ccf, .thickness = 0.05};
    for (int k = 0; k < count; ++k) {
        planner::Toolpath fibre{planner::PathRole::fibre, false, {}};
        for (int i = 0; i <= length / 10; ++i) fibre.points.emplace_back(100 + 10.0 * i, 145 + 10.0 * k);
        ccf.paths.push_back(fibre);
    }
    return ccf;
}

inline abb::PrintProgram make_program(const std::vector<planner::ToolpathLayer>& layers) {
    return abb::build_print_program(layers, abb::RobotCellConfig{},
                                    {.pla_speed_mm_s = pla_speed, .ccf_speed_mm_s = ccf_speed,
                                     .cutter_distance_mm = 42});
}

// Every board command of a whole print, in order: the pre-flight heat-up, the engine's start,
// then each event's commands (hotends are hot at every head switch). `first_line`, when given,
// gets the index of each event's first command (by sequence; none: absent).
inline std::vector<std::string> expected_board_log(const abb::PrintProgram& program,
                                                   std::map<int, std::size_t>* first_line = nullptr) {
    drivers::ExtruderController ref{drivers::ExtruderConfig{}};
    const double d = ref.config().filament_diameter_mm;
    const double pla_ratio = 0.8 * 0.8 / (std::numbers::pi * d * d / 4);
    std::vector<std::string> out;
    const auto add = [&](const std::vector<std::string>& lines) {
        out.insert(out.end(), lines.begin(), lines.end());
    };
    add(ref.prepare({}, false));
    add(ref.prepare({}, true));
    add(ref.prepare({}, false));
    for (const abb::ProgramEvent& e : program.events) {
        const auto head = e.nozzle == abb::Nozzle::pla ? drivers::Head::pla : drivers::Head::ccf;
        if (first_line) (*first_line)[e.sequence] = out.size();
        switch (e.kind) {
            case EventKind::head_switch: add(ref.select(head)); break;
            case EventKind::extrude_on:
                add(ref.prime());
                add(metered_pieces(e.length_mm, pla_ratio, e.speed_mm_s, 2));
                break;
            case EventKind::extrude_off: add(ref.retract()); break;
            case EventKind::fibre_start:
                add(ref.thread_fibre());
                out.push_back("M400");
                add(metered_pieces(e.length_mm, 1.0, e.speed_mm_s, 1));
                break;
            case EventKind::cut: add(ref.cut()); break;
            case EventKind::path_end:
            case EventKind::layer_end: break;
        }
    }
    return out;
}

class PrintCellTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string tmpl = (std::filesystem::temp_directory_path() / "print-XXXXXX").string();
        dir_ = mkdtemp(tmpl.data());
        drivers::sim::SimCellOptions co;
        co.time_scale = scale_;
        co.main_module = std::string(FIBRECELL_SOURCE_DIR) + "/drivers/abb/rapid/FcMain.mod";
        cell_ = std::make_unique<drivers::sim::SimCell>(co);

        drivers::sim::MockGt2560Options mo;
        mo.time_scale = scale_;
        mo.bootloader_s = 0.2;
        mo.hotend_tau_s = 0.5;
        mo.residency_s = 0.2;
        mo.link_path = (dir_ / "ttyGT2560").string();
        mock_ = std::make_unique<drivers::sim::MockGt2560>(mo);
        drivers::marlin::MarlinLinkConfig lc;
        lc.serial.device = mock_->port_path();
        board_.configure(lc);
        board_.on_temperature([this](const auto& r) {
            std::lock_guard lock(mu_);
            if (session_) session_->board_temperature(r);
        });
        board_.activate();

        rws_ = std::make_unique<abb::rws::RwsClient>(
            abb::rws::RwsClientConfig{.port = cell_->rws_port()});
        abb::RobotIoConfig rc;
        rc.host = "127.0.0.1";
        rc.port = cell_->modbus_port();
        rc.poll_period = 2ms;
        rc.stable_reads = 1;
        rc.response_timeout = 200ms;
        rc.heartbeat_period = 20ms;
        rc.robot_heartbeat_timeout = 500ms;
        rc.reconnect_backoff_min = 20ms;
        rc.reconnect_backoff_max = 100ms;
        rc.stats_log_period = 0s;
        robot_ = std::make_unique<abb::RobotIoLink>(rc);
        robot_->on_event([this](const auto& c) {
            std::lock_guard lock(mu_);
            if (session_) session_->robot_event(c);
        });
        robot_->on_state([this](const auto& c) {
            std::lock_guard lock(mu_);
            if (session_) session_->robot_link_state(c);
        });
        robot_->start();
        ASSERT_TRUE(robot_->wait_until_up(5s)) << robot_->snapshot().last_error;
        job_start_ = mock_->executed_count();
    }

    void TearDown() override {
        {
            std::lock_guard lock(mu_);
            session_.reset();
        }
        if (robot_) robot_->stop();
        board_.on_temperature(nullptr);
        if (board_.state() == drivers::DeviceState::active) board_.deactivate();
        robot_.reset();
        rws_.reset();
        cell_.reset();
        mock_.reset();
        if (!dir_.empty()) std::filesystem::remove_all(dir_);
    }

    // RAPID chunks of the program (small chunks so that FcMain loads several).
    static std::vector<abb::ChunkFile> chunks_of(const abb::PrintProgram& program) {
        std::vector<abb::ChunkFile> out;
        for (const auto& m : abb::write_rapid_chunks(program, abb::RobotCellConfig{}, {.max_lines = 36}).modules)
            out.push_back({m.file_name, m.text});
        return out;
    }

    PrintOptions options() const {
        PrintOptions o;
        o.heartbeat_timeout_s = 0.5;  // real s: the simulated controller scales it
        o.max_chunk_lines = 36;
        o.sync.time_scale = scale_;
        return o;
    }

    // The session prints a copy of `program` kept by the fixture, so that it outlives the
    // session even when a test ends early.
    void make_session(const abb::PrintProgram& program, std::vector<abb::ChunkFile> chunks,
                      PrintOptions o) {
        program_ = program;
        auto s = std::make_unique<PrintSession>(program_, std::move(chunks),
                                                daemon::print::PrintLinks{*rws_, *robot_, board_, extruder_}, o);
        std::lock_guard lock(mu_);
        session_ = std::move(s);
    }

    std::vector<std::string> executed_job() const {
        std::vector<std::string> out;
        const auto log = mock_->executed();
        for (std::size_t i = job_start_; i < log.size(); ++i) out.push_back(log[i].text);
        return out;
    }
    std::vector<drivers::sim::ExecutedCommand> executed_job_entries() const {
        const auto log = mock_->executed();
        return {log.begin() + static_cast<std::ptrdiff_t>(job_start_), log.end()};
    }

    // Where the robot's TCP (bed frame) was when the board executed something at its time t_s
    // (after the last sample the robot stands where it stopped).
    std::optional<Eigen::Vector3d> robot_at_board_time(
        const std::vector<drivers::sim::TrajectorySample>& trajectory, double board_t_s) const {
        const auto wall = mock_->wall_at(board_t_s);
        if (!trajectory.empty() && wall > trajectory.back().wall) return trajectory.back().tcp_wobj_mm;
        const auto s = drivers::sim::sample_at(trajectory, wall);
        if (!s) return std::nullopt;
        return s->tcp_wobj_mm;
    }

    // How far off `point` (a path's start or end) the robot was when the board acted at its
    // simulated time `board_t_s`, in mm along the robot's path. Where the robot stood at the
    // point, the time it stood there before the action (`at_end`: since it arrived) or after it
    // (a start: until it left) counts at `speed_mm_s`: feed that goes on after the robot stopped
    // at a path's end, or starts before it leaves, is as far off as feed a distance away.
    std::optional<double> path_error_mm(const std::vector<drivers::sim::TrajectorySample>& trajectory,
                                        const Eigen::Vector3d& point, double board_t_s,
                                        bool at_end, double speed_mm_s) const {
        if (trajectory.empty()) return std::nullopt;
        const auto wall = mock_->wall_at(board_t_s);
        const bool after_all = wall > trajectory.back().wall;
        const auto robot = after_all ? std::optional(trajectory.back())
                                     : drivers::sim::sample_at(trajectory, wall);
        if (!robot) return std::nullopt;
        // The stays at the point: runs of samples there; the one nearest the action in time.
        std::optional<std::pair<std::size_t, std::size_t>> stay;
        double nearest = 0;
        for (std::size_t i = 0; i < trajectory.size(); ++i) {
            if ((trajectory[i].tcp_wobj_mm - point).norm() > 1e-3) continue;
            std::size_t j = i;
            while (j + 1 < trajectory.size() && (trajectory[j + 1].tcp_wobj_mm - point).norm() <= 1e-3) ++j;
            const auto in = trajectory[i].wall, out = trajectory[j].wall;
            const double gap = wall < in ? seconds(in - wall) : wall > out ? seconds(wall - out) : 0;
            if (!stay || gap < nearest) stay = {i, j}, nearest = gap;
            i = j;
        }
        if (!stay) return std::nullopt;
        const auto& in = trajectory[stay->first];
        const auto& out = trajectory[stay->second];
        const bool stands_to_the_end = stay->second + 1 == trajectory.size();
        if (wall < in.wall) return in.path_mm - robot->path_mm;
        if (wall > out.wall && !stands_to_the_end) return robot->path_mm - out.path_mm;
        const double stood_s = at_end ? seconds(wall - in.wall) : seconds(out.wall - wall);
        return std::max(0.0, stood_s) * scale_ * speed_mm_s;
    }

    static double seconds(std::chrono::steady_clock::duration d) {
        return std::chrono::duration<double>(d).count();
    }

    double scale_ = print_time_scale;  // a derived fixture may lower it in its constructor
    std::filesystem::path dir_;
    std::unique_ptr<drivers::sim::SimCell> cell_;
    std::unique_ptr<drivers::sim::MockGt2560> mock_;
    drivers::marlin::MarlinLink board_;
    drivers::ExtruderController extruder_{drivers::ExtruderConfig{}};
    std::unique_ptr<abb::rws::RwsClient> rws_;
    std::unique_ptr<abb::RobotIoLink> robot_;
    std::mutex mu_;
    abb::PrintProgram program_;
    std::unique_ptr<PrintSession> session_;
    std::size_t job_start_ = 0;
};

}  // namespace fibrecell::test
