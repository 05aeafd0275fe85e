#pragma once
// A GT2560 Rev A that runs real ATmega2560 firmware (an ELF or Intel HEX build: stock Marlin, or
// the project's test firmware) in libsimavr, at real time and never faster, with UART0 on a
// pseudo-terminal of its own and the board's world around the MCU: two hotends with a thermal
// model on the heater pins and thermistor voltages on ADC8/ADC9, the extruders' step pulses
// counted, the cutter/servo pin's edges, and faults on the wire, pauses, unplugging and MCU
// resets on command. docs/board-simulator.md says how to use it; the gt2560-avr tool wraps it.
//
// simavr 1.6 needs two work-arounds (../shared/hil/marlin-1.1.9-gt2560/README.md): the UART's
// poll-sleep is turned off (else simulated time crawls), and UDRE is set when the firmware turns
// the transmitter on (else the first serial write waits forever).

#include "drivers/sim/avr/board_pins.hpp"
#include "drivers/sim/avr/hotend_thermal.hpp"
#include "drivers/sim/avr/wire_faults.hpp"

#include <memory>
#include <string>

namespace fibrecell::drivers::sim::avr {

struct AvrBoardOptions {
    std::string firmware;             // .elf or .hex for an ATmega2560
    std::string link_path;            // the pty's symlink (several boards: one each); may be empty
    std::string edge_log;             // every pin edge "<simulated s> <pin> <0|1>"; empty: none
    std::uint32_t frequency_hz = 16'000'000;
    BoardPinsOptions pins;
    HotendThermalOptions hotend;
    std::uint32_t fault_seed = 1;
};

enum class WireSide { to_board, from_board };

class AvrBoard {
  public:
    // Loads the firmware and starts it. Throws std::runtime_error naming the file and what is
    // wrong with it (missing, not an AVR image, too big for the flash).
    explicit AvrBoard(AvrBoardOptions options);
    ~AvrBoard();
    AvrBoard(const AvrBoard&) = delete;
    AvrBoard& operator=(const AvrBoard&) = delete;

    std::string port_path() const;

    // Each control call returns once the simulation has acted on it.
    // Faults, applied from the next byte on.
    void set_wire_faults(WireSide side, const WireFaultRates& rates);
    // The MCU stops for `seconds` of real time (its clock too), then goes on where it was.
    void pause(double seconds);
    void unplug();                    // the pty closes: the host sees the cable pulled
    void replug();                    // a new pty behind the same symlink
    void reset();                     // the MCU's reset line, as a brown-out or watchdog would

    // Everything a test measures, as one JSON object (docs/board-simulator.md, "Status"); the
    // edge log is flushed with it.
    std::string status_json() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fibrecell::drivers::sim::avr
