// The hotend model against its closed form, and the thermistor voltage against table 1's
// definition at known points.
#include "drivers/sim/avr/hotend_thermal.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fibrecell::drivers::sim::avr;

TEST(HotendThermal, HeatsTowardsPowerOverLossWithTimeConstantCOverK) {
    const HotendThermalOptions o{.power_w = 40, .loss_w_per_k = 0.2, .heat_capacity_j_per_k = 4,
                                 .ambient_c = 20};
    // Stepped in 1 ms pieces for 10 s at full duty: T = Ta + P/k (1 - exp(-t k / C)).
    double t = o.ambient_c;
    for (int i = 0; i < 10'000; ++i) t = hotend_step(t, 1.0, 1e-3, o);
    EXPECT_NEAR(t, 20 + 200 * (1 - std::exp(-10 * 0.2 / 4)), 1e-9);
    // Off, it cools back towards ambient by the same time constant.
    const double hot = t;
    for (int i = 0; i < 5'000; ++i) t = hotend_step(t, 0.0, 1e-3, o);
    EXPECT_NEAR(t, 20 + (hot - 20) * std::exp(-5 * 0.2 / 4), 1e-9);
    // Half duty settles at half the rise.
    EXPECT_NEAR(hotend_step(20, 0.5, 1e6, o), 20 + 100, 1e-9);
}

TEST(HotendThermal, ThermistorVoltageFollowsTableOneOnTheBoardsPullUp) {
    // 25 C: the thermistor's nominal 100 kOhm against 4.7 kOhm.
    EXPECT_NEAR(thermistor_millivolts(25), 5000.0 * 100 / 104.7, 1e-6);
    // 200 C: R = 100k exp(4092 (1/473.15 - 1/298.15)) = 614.5 Ohm.
    const double r = 100e3 * std::exp(4092 * (1 / 473.15 - 1 / 298.15));
    EXPECT_NEAR(thermistor_millivolts(200), 5000 * r / (r + 4700), 1e-6);
    EXPECT_GT(thermistor_millivolts(100), thermistor_millivolts(200));  // NTC: hotter, lower
}
