// Pin edges into what the board did: steps counted only when the driver is enabled, signed by
// the direction pin, heater on-time, servo pulses on D11.
#include "drivers/sim/avr/board_pins.hpp"

#include <gtest/gtest.h>

#include <sstream>

using namespace fibrecell::drivers::sim::avr;

namespace {

void pulses(BoardPins& p, BoardPin step, int n, double& t) {
    for (int i = 0; i < n; ++i) {
        p.edge(step, true, t += 1e-4);
        p.edge(step, false, t += 1e-4);
    }
}

}  // namespace

TEST(BoardPins, CountsStepsWhileEnabledSignedByDirection) {
    std::ostringstream log;
    BoardPins p({.steps_per_mm = 100}, &log);
    double t = 0;
    p.edge(BoardPin::e0_enable, true, t);      // disabled (active low)
    pulses(p, BoardPin::e0_step, 5, t);
    p.edge(BoardPin::e0_enable, false, t += 1e-3);
    p.edge(BoardPin::e0_dir, true, t);         // forward
    pulses(p, BoardPin::e0_step, 250, t);
    p.edge(BoardPin::e0_dir, false, t);
    pulses(p, BoardPin::e0_step, 50, t);
    const ExtruderSteps& e = p.extruder(0);
    EXPECT_EQ(e.while_disabled, 5);
    EXPECT_EQ(e.forward, 250);
    EXPECT_EQ(e.backward, 50);
    EXPECT_EQ(e.net_steps, 200);
    EXPECT_DOUBLE_EQ(p.extruded_mm(0), 2.0);
    EXPECT_EQ(p.extruder(1).net_steps, 0);
    // Every change is logged once: 2 x 305 step edges, enable twice, dir twice.
    std::size_t lines = 0;
    for (char c : log.str()) lines += c == '\n';
    EXPECT_EQ(lines, 2u * 305 + 4);
}

TEST(BoardPins, InvertedDirectionCountsTheOtherWay) {
    BoardPins p({.steps_per_mm = 105, .invert_e_dir = true});
    double t = 0;
    p.edge(BoardPin::e1_dir, true, t);
    pulses(p, BoardPin::e1_step, 105, t);
    EXPECT_EQ(p.extruder(1).net_steps, -105);
}

TEST(BoardPins, HeaterAndFanOnTimeIsSplitAtEachTake) {
    BoardPins p;
    p.edge(BoardPin::heater0, true, 1.0);
    p.edge(BoardPin::heater0, false, 1.25);
    EXPECT_NEAR(p.take_on_s(BoardPin::heater0, 2.0), 0.25, 1e-12);
    p.edge(BoardPin::heater0, true, 2.5);
    EXPECT_NEAR(p.take_on_s(BoardPin::heater0, 3.0), 0.5, 1e-12);  // still on: counted up to the take
    p.edge(BoardPin::heater0, false, 3.25);
    EXPECT_NEAR(p.take_on_s(BoardPin::heater0, 4.0), 0.25, 1e-12);
    EXPECT_NEAR(p.take_on_s(BoardPin::heater1, 4.0), 0.0, 1e-12);
    // The part fan's PWM, counted the same way for the hotends' extra loss.
    p.edge(BoardPin::fan, true, 4.0);
    p.edge(BoardPin::fan, false, 4.002);
    p.edge(BoardPin::fan, true, 4.004);
    EXPECT_NEAR(p.take_on_s(BoardPin::fan, 4.005), 0.003, 1e-12);
}

TEST(BoardPins, ServoPulseWidthAndCutterEdgesOnD11) {
    BoardPins p;
    p.edge(BoardPin::d11, true, 0.020);
    p.edge(BoardPin::d11, false, 0.020 + 1472e-6);
    EXPECT_NEAR(p.servo_pulse_us(), 1472, 1e-6);
    p.edge(BoardPin::d11, true, 1.0);  // a cutter held for 200 ms is no servo pulse
    p.edge(BoardPin::d11, false, 1.2);
    EXPECT_NEAR(p.servo_pulse_us(), 1472, 1e-6);
    ASSERT_EQ(p.d11_edges().size(), 4u);
    EXPECT_DOUBLE_EQ(p.d11_edges()[2].t_s, 1.0);
    EXPECT_TRUE(p.d11_edges()[2].level);
}
