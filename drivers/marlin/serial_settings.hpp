#pragma once
// What a serial port is opened with, and the error that says why it could not be: apart from
// serial_port.hpp so that the link's configuration does not bring Boost.Asio along.

#include <stdexcept>
#include <string>

namespace fibrecell::drivers::marlin {

class SerialError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct SerialSettings {
    std::string device;             // /dev/serial/by-id/... or /dev/ttyUSB0
    int baud_rate = 250000;
    // HUPCL drops DTR on close, so the next open resets an Arduino board. Off by default: a
    // daemon restart then does not reboot the board mid-job (it still resets on first open).
    bool hangup_on_close = false;
    bool exclusive = true;          // TIOCEXCL: a second opener gets EBUSY
};

}  // namespace fibrecell::drivers::marlin
