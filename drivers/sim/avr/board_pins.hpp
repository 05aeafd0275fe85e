#pragma once
// What the GT2560's pins did, as a test of the firmware wants to know it: every edge of the
// extruder, heater and D11 (cutter or servo) pins with its simulated time, the extruders' step
// pulses counted into millimetres, the heaters' on-time for the thermal model, and the servo
// pulse width. Fed by the board simulator's pin callbacks; no simavr in here, so it is tested
// on its own.

#include <array>
#include <cstdint>
#include <deque>
#include <ostream>

namespace fibrecell::drivers::sim::avr {

enum class BoardPin : std::uint8_t {
    e0_step, e0_dir, e0_enable,  // D43 PL6, D45 PL4, D41 PG0 (enable active low)
    e1_step, e1_dir, e1_enable,  // D49 PL0, D47 PL2, D48 PL1
    heater0, heater1,            // D2 PE4, D3 PE5
    d11,                         // PB5: M42 P11 (the cutter) or the servo header
    fan,                         // D7 PH4
};
inline constexpr int board_pin_count = 10;
const char* pin_name(BoardPin p);

struct PinEdge {
    double t_s = 0;
    BoardPin pin = BoardPin::d11;
    bool level = false;
};

// One extruder's motor as its driver sees the pins.
struct ExtruderSteps {
    std::int64_t net_steps = 0;       // forward minus backward, while enabled
    std::int64_t forward = 0, backward = 0;
    std::int64_t while_disabled = 0;  // pulses the driver ignored (enable high)
    double first_step_s = -1, last_step_s = -1;
};

struct BoardPinsOptions {
    double steps_per_mm = 105;        // E steps/mm of the firmware build
    bool invert_e_dir = false;        // dir high = forward unless inverted (INVERT_E0_DIR)
    std::size_t d11_edges_kept = 10'000;  // the oldest go first (a servo pulses at 50 Hz)
};

class BoardPins {
  public:
    explicit BoardPins(BoardPinsOptions o = {}, std::ostream* edge_log = nullptr);

    // A pin changed (or was written with the same level: ignored) at simulated time t_s.
    void edge(BoardPin pin, bool level, double t_s);
    // The MCU reset: every output pin is an input again (low).
    void reset(double t_s);

    bool level(BoardPin pin) const { return levels_[static_cast<int>(pin)]; }
    const ExtruderSteps& extruder(int e) const { return extruders_[e]; }
    double extruded_mm(int e) const { return extruders_[e].net_steps / o_.steps_per_mm; }
    const std::deque<PinEdge>& d11_edges() const { return d11_; }
    std::uint64_t edges(BoardPin pin) const { return counts_[static_cast<int>(pin)]; }
    // The last high pulse on D11 shorter than 3 ms (a servo pulse) [us]; 0 if none.
    double servo_pulse_us() const { return servo_pulse_us_; }
    // A heater's or the fan's on-time since the last call for it, up to t_s [s] (other pins: 0).
    double take_on_s(BoardPin pin, double t_s);
    const BoardPinsOptions& options() const { return o_; }

  private:
    BoardPinsOptions o_;
    std::ostream* log_;
    std::array<bool, board_pin_count> levels_{};
    std::array<double, board_pin_count> since_s_{};
    std::array<std::uint64_t, board_pin_count> counts_{};
    std::array<ExtruderSteps, 2> extruders_{};
    std::array<double, board_pin_count> on_s_{};     // the heaters' and fan's on-time not taken
    std::array<double, board_pin_count> taken_s_{};
    std::deque<PinEdge> d11_;
    double servo_pulse_us_ = 0;
};

}  // namespace fibrecell::drivers::sim::avr
