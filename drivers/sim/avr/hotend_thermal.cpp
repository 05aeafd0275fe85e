#include "drivers/sim/avr/hotend_thermal.hpp"

#include <cmath>

namespace fibrecell::drivers::sim::avr {

double hotend_step(double temp_c, double duty, double dt_s, const HotendThermalOptions& o) {
    // Steady state for this duty, approached with time constant C / k.
    const double steady_c = o.ambient_c + duty * o.power_w / o.loss_w_per_k;
    const double decay = std::exp(-dt_s * o.loss_w_per_k / o.heat_capacity_j_per_k);
    return steady_c + (temp_c - steady_c) * decay;
}

double thermistor_millivolts(double temp_c) {
    constexpr double beta = 4092, r25_ohm = 100'000, t25_k = 298.15, pullup_ohm = 4'700;
    const double r = r25_ohm * std::exp(beta * (1.0 / (temp_c + 273.15) - 1.0 / t25_k));
    return 5000.0 * r / (r + pullup_ohm);
}

}  // namespace fibrecell::drivers::sim::avr
