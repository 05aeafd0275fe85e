#pragma once
// A hotend as the board's thermistor sees it: one lumped heat capacity heated by its cartridge
// and losing heat in proportion to its rise over the air (first order), more with the part fan
// blowing; and the EPCOS 100k thermistor of Marlin's table 1 on the GT2560's 4.7 kOhm pull-up.
// The default figures are a 40 W / 12 V cartridge in an aluminium block, derived in
// docs/board-simulator.md ("The hotend model"): it holds 200 C at 22% and 250 C at 28% of full
// power in still air, as real 40 W hotends do, and reaches 250 C in about a minute.

namespace fibrecell::drivers::sim::avr {

struct HotendThermalOptions {
    double power_w = 40;                 // the heater cartridge at full duty
    double loss_w_per_k = 0.05;          // still air, per kelvin above ambient
    double fan_loss_w_per_k = 0.04;      // added with the part fan at full duty
    double heat_capacity_j_per_k = 10;   // block, nozzle and cartridge
    double ambient_c = 25;
};

// The temperature after `dt_s` with the heater on for `duty` (0..1) of it and the part fan for
// `fan_duty` [deg C]: the exact solution of C dT/dt = duty P - (k + fan k_fan)(T - T_amb).
double hotend_step(double temp_c, double duty, double fan_duty, double dt_s,
                   const HotendThermalOptions& o);

// The thermistor's resistance at a temperature [ohm], from the EPCOS 100k table
// (drivers/sim/avr/epcos_100k.h), extended beyond its rows by the end rows' slope.
double thermistor_ohms(double temp_c);

// The thermistor's voltage at the ADC pin [mV]: 5 V R / (R + 4.7 kOhm).
double thermistor_millivolts(double temp_c);

}  // namespace fibrecell::drivers::sim::avr
