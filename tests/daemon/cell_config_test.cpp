#include "daemon/cell_config.hpp"

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
