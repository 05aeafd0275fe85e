#pragma once
// A small real cell for the sync engine tests: the mock GT2560 on a pseudo-terminal behind a real
// MarlinLink, the simulated controller's Modbus server on a loopback ephemeral port behind a real
// RobotIoLink, and a two-layer print program (a 20 mm PLA square, then a straight 100 mm fibre
// path). The test plays the robot through the server; nothing of the project is mocked. The
// expected board log is built here from a second ExtruderController and the metering rule.
#include "daemon/sync/sync_engine.hpp"
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/sim/robot_io/robot_io_server.hpp"
#include "drivers/abb/program/print_program.hpp"
#include "drivers/extruder/extruder_controller.hpp"
#include "drivers/marlin/marlin_link.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"
#include "metered_pieces.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <mutex>
#include <numbers>
#include <thread>

namespace fibrecell::test {

using namespace std::chrono_literals;
using daemon::sync::EventDone;
using daemon::sync::SyncEngine;
using daemon::sync::SyncOptions;
using daemon::sync::SyncStatus;
using drivers::Head;
using drivers::abb::EventKind;

constexpr double time_scale = 20;  // the mock board and the pacing: 20 simulated s per real s

// Layer 0: a closed 20 mm PLA square (80 mm); layer 1: a straight 100 mm fibre path.
inline drivers::abb::PrintProgram two_layer_program() {
    namespace abb = drivers::abb;
    abb::RobotLayer pla{.index = 0, .z = 0.8, .nozzle = abb::Nozzle::pla};
    pla.paths.push_back({true, {{140, 140}, {160, 140}, {160, 160}, {140, 160}}});
    abb::RobotLayer ccf{.index = 1, .z = 0.85, .nozzle = abb::Nozzle::ccf};
    abb::RobotPath fibre{false, {}};
    for (int i = 0; i <= 10; ++i) fibre.points.emplace_back(100 + 10.0 * i, 150);
    ccf.paths.push_back(fibre);
    return drivers::abb::build_print_program(
        {pla, ccf}, drivers::abb::RobotCellConfig{},
        {.pla_speed_mm_s = 12, .ccf_speed_mm_s = 5, .cutter_distance_mm = 42});
}

inline void append(std::vector<std::string>& to, const std::vector<std::string>& lines) {
    to.insert(to.end(), lines.begin(), lines.end());
}

// Sum of the E of every "G1 E" line in `lines[from, to)`.
inline double sum_e(const std::vector<std::string>& lines, std::size_t from, std::size_t to) {
    double e = 0;
    for (std::size_t i = from; i < to && i < lines.size(); ++i)
        if (lines[i].rfind("G1 E", 0) == 0) e += std::stod(lines[i].substr(4));
    return e;
}

class SyncCellTest : public ::testing::Test {
  protected:
    // The board and the robot I/O up; with `preheat` both hotends at temperature first (the
    // mock's hotends have a short time constant so that this takes a fraction of a second).
    void boot(bool preheat = true) {
        drivers::sim::MockGt2560Options mo;
        mo.time_scale = time_scale;
        mo.bootloader_s = 0.2;  // 10 ms real
        mo.hotend_tau_s = 0.5;
        mo.residency_s = 0.2;
        mo.link_path = (dir_ / "ttyGT2560").string();
        mock_ = std::make_unique<drivers::sim::MockGt2560>(mo);
        drivers::marlin::MarlinLinkConfig lc;
        lc.serial.device = mock_->port_path();
        board_.configure(lc);
        board_.activate();
        if (preheat) {
            drivers::ExtruderController heater{drivers::ExtruderConfig{}};
            auto done = board_.submit(heater.prepare({}, true));
            ASSERT_EQ(done.wait_for(20s), std::future_status::ready);
            ASSERT_TRUE(done.get().ok());
        }

        drivers::sim::RobotIoServerOptions so;
        so.robot_heartbeat_period = 20ms;
        server_ = std::make_unique<drivers::sim::RobotIoServer>(drivers::abb::RobotIoMap{}, so);
        drivers::abb::RobotIoConfig rc;
        rc.host = server_->host();
        rc.port = server_->port();
        rc.poll_period = 2ms;
        rc.stable_reads = 1;
        rc.response_timeout = 200ms;
        rc.heartbeat_period = 20ms;
        rc.robot_heartbeat_timeout = 500ms;
        rc.reconnect_backoff_min = 20ms;
        rc.reconnect_backoff_max = 100ms;
        rc.stats_log_period = 0s;
        robot_ = std::make_unique<drivers::abb::RobotIoLink>(rc);
    }

    // The engine wired to the links as the service does; the robot link starts here. With
    // `preheated`, waits until the engine has read both hotends (at temperature by then).
    void start_engine(SyncOptions o = {}, bool preheated = true) {
        o.time_scale = time_scale;
        engine_ = std::make_unique<SyncEngine>(program_, extruder_, board_, *robot_, o);
        engine_->on_event_done([this](const EventDone& d) {
            std::lock_guard lock(mu_);
            done_.push_back(d);
        });
        engine_->on_fault([this](const std::string& reason) {
            std::lock_guard lock(mu_);
            faults_.push_back(reason);
        });
        engine_->on_progress([this](const daemon::sync::SyncProgress& p) {
            std::lock_guard lock(mu_);
            progress_layers_.push_back(p.layer);
        });
        robot_->on_event([this](const auto& c) { engine_->robot_event(c); });
        robot_->on_state([this](const auto& c) { engine_->robot_link_state(c); });
        board_.on_temperature([this](const auto& r) { engine_->board_temperature(r); });
        robot_->start();
        ASSERT_TRUE(robot_->wait_until_up(5s)) << robot_->snapshot().last_error;
        job_start_ = mock_->executed_count();
        engine_->start();
        if (preheated) {
            ASSERT_TRUE(eventually([&] {
                const SyncStatus s = engine_->status();
                return s.pla_hotend_c && s.ccf_hotend_c;
            }));
        }
    }

    void TearDown() override {
        if (robot_) robot_->stop();
        board_.on_temperature(nullptr);
        engine_.reset();
        if (board_.state() == drivers::DeviceState::active) board_.deactivate();
        server_.reset();
        mock_.reset();
    }

    // The robot reaches event `n`; at a barrier it waits for the release like FcBarrier. Events
    // are at least a poll apart, as on the real path (a gap is made on purpose).
    void robot_at(int n) {
        const auto& e = program_.events.at(static_cast<std::size_t>(n - 1));
        if (e.barrier) server_->set_barrier_number(static_cast<std::uint16_t>(n));
        server_->set_event_number(static_cast<std::uint16_t>(n));
        ASSERT_TRUE(eventually([&] { return engine_->status().last_received >= n; }))
            << "event " << n << " not received";
        if (e.barrier) {
            ASSERT_TRUE(server_->wait_for_commands([&](const auto& c) { return c.release == n; }, 10s))
                << "barrier " << n << " not released; engine: " << engine_->status().fault_reason;
        }
    }

    // Waits until the board has executed `n` commands of the job.
    void board_ran(std::size_t n) {
        ASSERT_TRUE(mock_->wait_for_executed(job_start_ + n, 10s))
            << "board ran " << executed_job().size() << " of " << n;
    }

    void confirmed(std::int64_t sequence) {
        ASSERT_TRUE(eventually([&] { return engine_->status().last_confirmed >= sequence; }))
            << "last confirmed " << engine_->status().last_confirmed;
    }

    // Every input posted to the engine so far has been handled: a marker temperature report
    // (the board's own reports cut off first) has come out of its queue behind them. For an
    // engine that is done with temperatures (a fault, the end of a test).
    void engine_handled_all_posted() {
        board_.on_temperature(nullptr);
        const double mark = -1000.0 - static_cast<double>(++markers_);
        drivers::marlin::TemperatureReport marker;
        marker.readings.push_back({"T0", mark, std::nullopt});
        engine_->board_temperature(marker);
        ASSERT_TRUE(eventually([&] { return engine_->status().pla_hotend_c == mark; }));
    }

    std::vector<std::string> executed_job() const {
        std::vector<std::string> out;
        const auto log = mock_->executed();
        for (std::size_t i = job_start_; i < log.size(); ++i) out.push_back(log[i].text);
        return out;
    }

    std::vector<EventDone> done() {
        std::lock_guard lock(mu_);
        return done_;
    }
    std::vector<std::string> faults() {
        std::lock_guard lock(mu_);
        return faults_;
    }
    std::vector<int> progress_layers() {
        std::lock_guard lock(mu_);
        return progress_layers_;
    }

    // The expected board commands, event by event, from a controller of the same configuration.
    struct Expected {
        drivers::ExtruderController ref{drivers::ExtruderConfig{}};
        std::vector<std::string> lines;
        SyncOptions options;

        double pla_ratio() const {
            const double d = ref.config().filament_diameter_mm;
            return options.pla_line_width_mm * options.pla_layer_height_mm / (std::numbers::pi * d * d / 4);
        }
        void start() { append(lines, ref.prepare({}, false)); }
        void head_switch(Head h) { append(lines, ref.select(h)); }
        void extrude_on(double path_mm, double speed) {
            append(lines, ref.prime());
            append(lines, metered_pieces(path_mm, pla_ratio(), speed, options.pla_piece_mm));
        }
        void extrude_off() { append(lines, ref.retract()); }
        void fibre_start(double path_mm, double speed) {
            append(lines, ref.thread_fibre());
            lines.push_back("M400");
            append(lines, metered_pieces(path_mm, 1.0, speed, options.fibre_piece_mm));
        }
        void cut() { append(lines, ref.cut()); }
    };

    TempDir dir_{"sync"};  // before the devices: the board's port link in it outlives the mock
    std::unique_ptr<drivers::sim::MockGt2560> mock_;
    drivers::marlin::MarlinLink board_;
    std::unique_ptr<drivers::sim::RobotIoServer> server_;
    std::unique_ptr<drivers::abb::RobotIoLink> robot_;
    drivers::abb::PrintProgram program_ = two_layer_program();
    drivers::ExtruderController extruder_{drivers::ExtruderConfig{}};
    std::unique_ptr<SyncEngine> engine_;
    std::size_t job_start_ = 0;
    int markers_ = 0;

    std::mutex mu_;
    std::vector<EventDone> done_;
    std::vector<std::string> faults_;
    std::vector<int> progress_layers_;
};

}  // namespace fibrecell::test
