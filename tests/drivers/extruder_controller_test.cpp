// The extruder controller's G-code, parsed back and checked against physical rules.
#include "drivers/extruder/extruder_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace fibrecell;
using namespace fibrecell::drivers;

namespace {

double param(const std::string& line, char key) {
    const auto p = line.find(std::string(" ") + key);
    return p == std::string::npos ? NAN : std::stod(line.substr(p + 2));
}

ExtruderConfig cell(const std::string& yaml = "") {
    return load_extruder_config(config::Section::load_text(yaml, "<test>"));
}

}  // namespace

TEST(ExtruderController, PlaExtrusionMatchesTheLineCrossSectionAndTcpSpeed) {
    ExtruderController ctl(cell("pla: {filament_diameter_mm: 1.75}\nmax_extrusion_length_mm: 50\n"));
    const auto g = ctl.extrude_pla(400.0, 12.0, 0.8, 0.8);  // paper: 0.8 mm lines, 12 mm/s
    ASSERT_FALSE(g.empty());
    EXPECT_EQ(g.front(), "T0");
    const double ratio = 0.8 * 0.8 / (std::numbers::pi * 1.75 * 1.75 / 4);
    double e = 0;
    for (std::size_t i = 1; i < g.size(); ++i) {
        EXPECT_EQ(g[i].rfind("G1 E", 0), 0u) << g[i];
        EXPECT_LE(param(g[i], 'E'), 50.0);  // split under Marlin's EXTRUDE_MAXLENGTH
        EXPECT_NEAR(param(g[i], 'F'), 12.0 * ratio * 60, 0.1);
        e += param(g[i], 'E');
    }
    EXPECT_NEAR(e, 400.0 * ratio, 1e-3);
    EXPECT_EQ(g.size(), 1u + static_cast<std::size_t>(std::ceil(400.0 * ratio / 50)));
}

TEST(ExtruderController, FibrePathThreadsFeedsAndCutsWithTheFeedStopped) {
    ExtruderController ctl(cell());
    std::vector<std::string> g = ctl.thread_fibre();
    for (auto& l : ctl.feed_fibre(458.0, 5.0)) g.push_back(l);  // 500 mm path minus 42 mm
    for (auto& l : ctl.cut()) g.push_back(l);
    ASSERT_GE(g.size(), 7u);
    EXPECT_EQ(g[0], "T1");
    EXPECT_DOUBLE_EQ(param(g[1], 'E'), 42.0);  // cutter distance threads the nozzle
    double fed = 0;
    std::size_t m400 = g.size(), cut = g.size();
    for (std::size_t i = 2; i < g.size(); ++i) {
        if (g[i].rfind("G1", 0) == 0) {
            EXPECT_LT(i, m400) << "no feed after the sync";
            EXPECT_DOUBLE_EQ(param(g[i], 'F'), 300.0);  // TCP speed 5 mm/s
            fed += param(g[i], 'E');
        }
        if (g[i] == "M400") m400 = i;
        if (g[i] == "M42 P11 S255") cut = i;
    }
    EXPECT_NEAR(fed, 458.0, 1e-6);
    EXPECT_LT(m400, cut);
    EXPECT_EQ(g.back(), "M42 P11 S0");
    EXPECT_TRUE(ctl.select(Head::ccf).empty());  // already selected
}

TEST(ExtruderController, ServoAndSpindleCuttersFromConfiguration) {
    ExtruderController servo(cell("cutter: {method: servo, servo_index: 0, cut_angle_deg: 120, open_angle_deg: 10, hold_ms: 300}\n"));
    EXPECT_EQ(servo.cut(), (std::vector<std::string>{"M400", "M280 P0 S120", "G4 P300", "M280 P0 S10"}));
    ExtruderController spindle(cell("cutter: {method: spindle}\n"));
    EXPECT_EQ(spindle.cut().front(), "M3 S255");  // M3 synchronises in the firmware
}

TEST(ExtruderController, RetractAndPrimeCancel) {
    ExtruderController ctl(cell("pla: {retract_mm: 2}\n"));
    const auto r = ctl.retract();
    const auto p = ctl.prime();
    EXPECT_DOUBLE_EQ(param(r.back(), 'E') + param(p.back(), 'E'), 0.0);
    EXPECT_LT(param(r.back(), 'E'), 0.0);
}

TEST(ExtruderConfig, RejectsUnknownKeysAndOutOfRangeValues) {
    EXPECT_THROW(cell("cutter: {pinn: 11}\n"), config::ConfigError);
    EXPECT_THROW(cell("link: {window_lines: 8}\n"), config::ConfigError);
    EXPECT_THROW(cell("pla: {tool: 1}\n"), config::ConfigError);  // same as ccf
    try {
        cell("ccf: {max_temp_c: 900}\n");
        FAIL();
    } catch (const config::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("ccf.max_temp_c"), std::string::npos) << e.what();
    }
    // The print temperature moved to the job; an old cell file says where.
    try {
        cell("pla: {temp_c: 200}\n");
        FAIL();
    } catch (const config::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("pla.temp_c: the print temperature is the job's"),
                  std::string::npos)
            << e.what();
    }
    const ExtruderConfig c = cell("link: {port: /dev/ttyUSB1, baud_rate: 115200, resend_ok: never}\n");
    EXPECT_EQ(c.link.serial.device, "/dev/ttyUSB1");
    EXPECT_EQ(c.link.serial.baud_rate, 115200);
    EXPECT_EQ(c.link.protocol.resend_ok, marlin::ResendOk::never);
}

TEST(ExtruderController, RejectsFeedsAboveTheLimit) {
    ExtruderController ctl(cell("max_feed_mm_s: 10\n"));
    EXPECT_THROW(ctl.feed_fibre(100, 20), std::invalid_argument);
    EXPECT_THROW(ctl.feed_fibre(-1, 5), std::invalid_argument);
}
