#include "drivers/sim/avr/board_pins.hpp"

#include <algorithm>

namespace fibrecell::drivers::sim::avr {

const char* pin_name(BoardPin p) {
    switch (p) {
        case BoardPin::e0_step: return "e0_step";
        case BoardPin::e0_dir: return "e0_dir";
        case BoardPin::e0_enable: return "e0_enable";
        case BoardPin::e1_step: return "e1_step";
        case BoardPin::e1_dir: return "e1_dir";
        case BoardPin::e1_enable: return "e1_enable";
        case BoardPin::heater0: return "heater0";
        case BoardPin::heater1: return "heater1";
        case BoardPin::d11: return "d11";
        case BoardPin::fan: return "fan";
    }
    return "?";
}

BoardPins::BoardPins(BoardPinsOptions o, std::ostream* edge_log) : o_(o), log_(edge_log) {}

void BoardPins::edge(BoardPin pin, bool level, double t_s) {
    const int i = static_cast<int>(pin);
    if (levels_[i] == level) return;
    const double was_since = since_s_[i];
    levels_[i] = level;
    since_s_[i] = t_s;
    ++counts_[i];
    if (log_) *log_ << t_s << ' ' << pin_name(pin) << ' ' << (level ? 1 : 0) << '\n';

    switch (pin) {
        case BoardPin::e0_step:
        case BoardPin::e1_step: {
            if (!level) break;  // a step is the rising edge
            const int e = pin == BoardPin::e0_step ? 0 : 1;
            const BoardPin dir = e == 0 ? BoardPin::e0_dir : BoardPin::e1_dir;
            const BoardPin enable = e == 0 ? BoardPin::e0_enable : BoardPin::e1_enable;
            ExtruderSteps& x = extruders_[e];
            if (this->level(enable)) {  // active low: high is off
                ++x.while_disabled;
                break;
            }
            const bool forward = this->level(dir) != o_.invert_e_dir;
            if (forward) ++x.forward;
            else ++x.backward;
            x.net_steps += forward ? 1 : -1;
            if (x.first_step_s < 0) x.first_step_s = t_s;
            x.last_step_s = t_s;
            break;
        }
        case BoardPin::heater0:
        case BoardPin::heater1:
        case BoardPin::fan:
            if (!level) on_s_[i] += t_s - std::max(was_since, taken_s_[i]);
            break;
        case BoardPin::d11:
            d11_.push_back({t_s, pin, level});
            if (d11_.size() > o_.d11_edges_kept) d11_.pop_front();
            if (!level && t_s - was_since < 3e-3) servo_pulse_us_ = (t_s - was_since) * 1e6;
            break;
        default: break;
    }
}

void BoardPins::reset(double t_s) {
    for (int i = 0; i < board_pin_count; ++i) edge(static_cast<BoardPin>(i), false, t_s);
}

double BoardPins::take_on_s(BoardPin pin, double t_s) {
    const int i = static_cast<int>(pin);
    double on = on_s_[i];
    if (level(pin)) on += t_s - std::max(since_s_[i], taken_s_[i]);
    on_s_[i] = 0;
    taken_s_[i] = t_s;
    return on;
}

}  // namespace fibrecell::drivers::sim::avr
