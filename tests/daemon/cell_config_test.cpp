#include "daemon/cell/cell_config.hpp"

#include "config/yaml_section.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

using namespace fibrecell;

TEST(CellConfig, ShippedSimulatedCellIsValid) {
    const auto c = daemon::load_cell_config(FIBRECELL_SOURCE_DIR "/config/cell-sim.yaml");
    EXPECT_EQ(c.name, "sim-cell");
    EXPECT_TRUE(c.simulated);
    EXPECT_EQ(c.extruder.link.serial.baud_rate, 250000);
}

TEST(CellConfig, ShippedIrc5CellIsValid) {
    const auto c = daemon::load_cell_config(FIBRECELL_SOURCE_DIR "/config/cell-irc5.yaml");
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
    const auto sim = daemon::load_cell_config(FIBRECELL_SOURCE_DIR "/config/cell-sim.yaml");
    EXPECT_EQ(sim.robot_io.stable_reads, 1);
    EXPECT_EQ(sim.rws.client.user, "Default User");
    EXPECT_EQ(sim.rws.job_dir, "fibrecell/job");
    const auto irc5 = daemon::load_cell_config(FIBRECELL_SOURCE_DIR "/config/cell-irc5.yaml");
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
