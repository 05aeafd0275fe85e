#pragma once
// A serial port on its POSIX descriptor, configured with termios and driven by Boost.Asio:
// raw 8N1, standard rates and 250000 (termios2/BOTHER), exclusive access, HUPCL chosen on
// purpose. Modem-control calls are best-effort: pseudo-terminals reject them (docs/marlin-link.md,
// "Reset on open").

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>

#include "drivers/marlin/serial_settings.hpp"

namespace fibrecell::drivers::marlin {

class SerialPort {
  public:
    explicit SerialPort(boost::asio::io_context& io) : stream_(io) {}
    ~SerialPort() { close(); }

    // Opens and configures the port; throws SerialError naming the device and the step.
    void open(const SerialSettings& settings);
    void close();
    bool is_open() const { return stream_.is_open(); }

    // Best effort (false when the device refuses, as ptys do).
    bool set_dtr(bool on);

    boost::asio::posix::stream_descriptor& stream() { return stream_; }

  private:
    boost::asio::posix::stream_descriptor stream_;
};

// Sets a non-standard rate through termios2 BOTHER (Linux); false when unsupported.
bool set_custom_baud(int fd, int baud_rate);

}  // namespace fibrecell::drivers::marlin
