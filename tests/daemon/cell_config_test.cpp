#include "daemon/cell/cell_config.hpp"

#include "config/yaml_section.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

using namespace fibrecell;

TEST(CellConfig, ShippedSimulatedCellIsValid) {
    const auto c = daemon::load_cell_config(fibrecell::test::source_path("config/cell-sim.yaml"));
    EXPECT_EQ(c.name, "sim-cell");
    EXPECT_TRUE(c.simulated);
    EXPECT_EQ(c.extruder.link.serial.baud_rate, 250000);
}

TEST(CellConfig, ShippedIrc5CellIsValid) {
    const auto c = daemon::load_cell_config(fibrecell::test::source_path("config/cell-irc5.yaml"));
    EXPECT_FALSE(c.simulated);
    EXPECT_EQ(c.robot.variant, fibrecell::drivers::abb::Irb1200Variant::irb1200_7_70);
}

TEST(CellConfig, ErrorsNameTheKeyPath) {
    const std::string path = ::testing::TempDir() + "fibrecell-bad-cell.yaml";
    std::ofstream(path) << "name: x\nextruder:\n  cutter: {method: laser}\n";
    try {
        daemon::load_cell_config(path);
        FAIL() << "expected an error";
    } catch (const config::ConfigError& e) {
        EXPECT_THAT(e.what(),
                    ::testing::HasSubstr("line 3: extruder.cutter.method: must be one of"));
    }
    std::remove(path.c_str());
}

TEST(CellConfig, RobotLinkSections) {
    const auto sim = daemon::load_cell_config(fibrecell::test::source_path("config/cell-sim.yaml"));
    EXPECT_EQ(sim.robot_io.stable_reads, 1);
    EXPECT_EQ(sim.rws.client.user, "Default User");
    EXPECT_EQ(sim.rws.job_dir, "fibrecell/job");
    const auto irc5 = daemon::load_cell_config(fibrecell::test::source_path("config/cell-irc5.yaml"));
    EXPECT_EQ(irc5.robot_io.host, "192.168.125.50");
    EXPECT_EQ(irc5.robot_io.stable_reads, 2);
    EXPECT_EQ(irc5.rws.client.host, "192.168.125.1");
    EXPECT_EQ(irc5.rws.client.port, 80);
}

TEST(CellConfig, RwsJobDirMustStayInHome) {
    const std::string path = ::testing::TempDir() + "fibrecell-bad-rws.yaml";
    for (const char* dir : {"../etc", "/abs", "a//b", "a b"}) {
        std::ofstream(path) << "rws: {job_dir: \"" << dir << "\"}\n";
        try {
            daemon::load_cell_config(path);
            FAIL() << "expected an error for " << dir;
        } catch (const config::ConfigError& e) {
            EXPECT_THAT(e.what(), ::testing::HasSubstr("rws.job_dir: must be a folder under HOME:"));
        }
    }
    std::remove(path.c_str());
}

namespace {

// The text as a cell YAML file of this test's own (CTest runs the tests of a file in parallel).
daemon::CellConfig load_text(const std::string& text) {
    fibrecell::test::TempDir dir("cell-config");
    const auto path = (dir.path() / "cell.yaml").string();
    std::ofstream(path) << text;
    return daemon::load_cell_config(path);
}

}  // namespace

TEST(CellConfig, AnExternalBoardIsPrintedThroughInRealTime) {
    EXPECT_FALSE(load_text("simulated: true\n").simulation.external_board);
    const auto c = load_text(
        "simulated: true\nsimulation: {time_scale: 1, board: external}\n"
        "extruder: {link: {port: /tmp/ttyGT2560}}\n");
    EXPECT_TRUE(c.simulation.external_board);
    EXPECT_FALSE(c.simulation.external_devices);  // the robot stays in-process
    EXPECT_EQ(c.extruder.link.serial.device, "/tmp/ttyGT2560");
    // devices: external has the board outside too.
    EXPECT_TRUE(load_text("simulated: true\nsimulation: {devices: external}\n").simulation.external_board);
    try {
        load_text("simulated: true\nsimulation: {time_scale: 20, board: external}\n");
        FAIL() << "expected an error";
    } catch (const config::ConfigError& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("simulation.board: an external board runs in real "
                                                   "time: set simulation.time_scale to 1 (it is 20)"));
    }
    EXPECT_THROW(load_text("simulated: true\nsimulation: {board: avr}\n"), config::ConfigError);
}

TEST(CellConfig, TheBoardSimulatorsHeatersComeFromTheSimulationSection) {
    const auto c = load_text("simulation: {heater_power_w: 30, heater_loss_w_per_k: 0.1, "
                             "heater_fan_loss_w_per_k: 0.07, heat_capacity_j_per_k: 6, ambient_c: 20}\n");
    EXPECT_DOUBLE_EQ(c.simulation.heater_power_w, 30);
    EXPECT_DOUBLE_EQ(c.simulation.heater_loss_w_per_k, 0.1);
    EXPECT_DOUBLE_EQ(c.simulation.heater_fan_loss_w_per_k, 0.07);
    EXPECT_DOUBLE_EQ(c.simulation.heat_capacity_j_per_k, 6);
    EXPECT_DOUBLE_EQ(c.simulation.ambient_c, 20);
    EXPECT_THROW(load_text("simulation: {heat_capacity_j_per_k: 0}\n"), config::ConfigError);
    EXPECT_THROW(load_text("simulation: {heater_fan_loss_w_per_k: -1}\n"), config::ConfigError);
    // The defaults: a real 40 W hotend (docs/board-simulator.md, "The hotend model").
    const auto d = load_text("");
    EXPECT_DOUBLE_EQ(d.simulation.heater_loss_w_per_k, 0.05);
    EXPECT_DOUBLE_EQ(d.simulation.heater_fan_loss_w_per_k, 0.04);
    EXPECT_DOUBLE_EQ(d.simulation.heat_capacity_j_per_k, 10);
    EXPECT_EQ(d.part_limits.max_tets, 300'000);
    EXPECT_THROW(load_text("part_limits: {max_tets: 0}\n"), config::ConfigError);
}
