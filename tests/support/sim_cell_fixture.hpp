#pragma once
// The simulated cell for end-to-end tests, built as the service builds it: CellDevices on a
// simulated cell YAML (the simulated IRC5 running the repo's FcMain.mod on loopback, the mock
// GT2560 on a pseudo-terminal, and the real drivers pointed at them: RwsClient, RobotIoLink,
// MarlinLink, ExtruderController). Only the settings are the tests': a time scale, hotends that
// heat in a fraction of a second, short robot I/O periods, and the whole trajectory kept.

#include "daemon/devices/cell_devices.hpp"
#include "drivers/sim/cell/sim_cell.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace fibrecell::test {

// A simulated cell YAML's settings for tests, with its state (the board's port link) in `state_dir`.
inline daemon::CellConfig sim_cell_config(const std::filesystem::path& state_dir, double time_scale) {
    using namespace std::chrono_literals;
    daemon::CellConfig c;
    c.name = "test-cell";
    c.state_dir = state_dir.string();
    c.simulated = true;
    c.simulation.time_scale = time_scale;
    c.simulation.hotend_tau_s = 0.5;
    c.simulation.residency_s = 0.2;
    c.simulation.main_module = fibrecell::test::source_path("drivers/abb/rapid/FcMain.mod");
    c.robot_io.poll_period = 2ms;
    c.robot_io.stable_reads = 1;
    c.robot_io.response_timeout = 1000ms;  // in-process on a loaded machine: no false link losses
    c.robot_io.heartbeat_period = 20ms;
    // The simulated controller runs in-process: under the sanitizers on a loaded machine its
    // heartbeat can stall for about a second (seen once at 963 ms) without anything being wrong.
    c.robot_io.robot_heartbeat_timeout = 2000ms;
    c.robot_io.reconnect_backoff_min = 20ms;
    c.robot_io.reconnect_backoff_max = 100ms;
    c.robot_io.stats_log_period = 0s;
    return c;
}

class SimCellFixture : public ::testing::Test {
  protected:
    // A derived fixture may change scale_ in its constructor.
    void SetUp() override {
        daemon::CellConfig c = sim_cell_config(dir_.path(), scale_);
        c.simulation.trajectory_samples = trajectory_samples_;
        devices_ = std::make_unique<daemon::devices::CellDevices>(c);
        ASSERT_NO_THROW(devices_->connect(std::chrono::seconds(20)));
        job_start_ = mock().executed_count();
    }
    void TearDown() override { devices_.reset(); }

    drivers::sim::SimCell& cell() { return *devices_->sim_cell(); }
    drivers::sim::MockGt2560& mock() const { return *devices_->mock_board(); }
    drivers::marlin::MarlinLink& board() { return devices_->board(); }
    drivers::abb::RobotIoLink& robot() { return devices_->robot_io(); }
    drivers::abb::rws::RwsClient& rws() { return devices_->links().rws; }

    // What the board executed since SetUp (after the handshake), in order.
    std::vector<drivers::sim::ExecutedCommand> executed_job_entries() const {
        return mock().executed_since(job_start_);
    }
    std::vector<std::string> executed_job() const {
        std::vector<std::string> out;
        for (const auto& e : executed_job_entries()) out.push_back(e.text);
        return out;
    }

    double scale_ = 20;  // simulated seconds per real second
    std::size_t trajectory_samples_ = 1'000'000;  // tests measure along the whole path
    TempDir dir_{"cell"};  // before the devices: the board's port link in it outlives them
    std::unique_ptr<daemon::devices::CellDevices> devices_;
    std::size_t job_start_ = 0;
};

}  // namespace fibrecell::test
