#pragma once
// A hotend as the board's thermistor sees it: one lumped heat capacity heated by its cartridge
// and losing heat to the air in proportion to the difference (first order), and the EPCOS 100k
// thermistor of Marlin's table 1 on the GT2560's 4.7 kOhm pull-up.

namespace fibrecell::drivers::sim::avr {

struct HotendThermalOptions {
    double power_w = 40;                 // the heater cartridge at full duty
    double loss_w_per_k = 0.12;          // to the air, per kelvin above ambient
    double heat_capacity_j_per_k = 5;    // block, nozzle and cartridge
    double ambient_c = 25;
};

// The temperature after `dt_s` with the heater on for `duty` (0..1) of it [deg C]: the exact
// solution of C dT/dt = duty P - k (T - T_amb) over the step.
double hotend_step(double temp_c, double duty, double dt_s, const HotendThermalOptions& o);

// The thermistor's voltage at the ADC pin [mV] for a temperature [deg C]:
// R = 100 kOhm exp(4092 (1/T - 1/298.15)), V = 5 V R / (R + 4.7 kOhm).
double thermistor_millivolts(double temp_c);

}  // namespace fibrecell::drivers::sim::avr
