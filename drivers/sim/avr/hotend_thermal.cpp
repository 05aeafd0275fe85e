#include "drivers/sim/avr/hotend_thermal.hpp"

#include "drivers/sim/avr/epcos_100k.h"

#include <algorithm>
#include <cmath>

namespace fibrecell::drivers::sim::avr {

double hotend_step(double temp_c, double duty, double fan_duty, double dt_s,
                   const HotendThermalOptions& o) {
    // Steady state for these duties, approached with time constant C / k.
    const double loss = o.loss_w_per_k + fan_duty * o.fan_loss_w_per_k;
    const double steady_c = o.ambient_c + duty * o.power_w / loss;
    const double decay = std::exp(-dt_s * loss / o.heat_capacity_j_per_k);
    return steady_c + (temp_c - steady_c) * decay;
}

double thermistor_ohms(double temp_c) {
    const double step = EPCOS_100K_STEP_C;
    const int row = std::clamp(static_cast<int>(std::floor((temp_c - EPCOS_100K_FIRST_C) / step)), 0,
                               EPCOS_100K_ROWS - 2);
    const double t0 = EPCOS_100K_FIRST_C + row * step + 273.15, t1 = t0 + step;
    const double x = (1 / (temp_c + 273.15) - 1 / t0) / (1 / t1 - 1 / t0);
    const double ln0 = std::log(epcos_100k_ohm[row]), ln1 = std::log(epcos_100k_ohm[row + 1]);
    return std::exp(ln0 + x * (ln1 - ln0));
}

double thermistor_millivolts(double temp_c) {
    const double r = thermistor_ohms(temp_c);
    return 5000.0 * r / (r + EPCOS_100K_PULLUP_OHM);
}

}  // namespace fibrecell::drivers::sim::avr
