#include "drivers/marlin/serial_port.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace fibrecell::drivers::marlin {
namespace {

speed_t standard_speed(int baud) {
    switch (baud) {
        case 9600: return B9600;
        case 19200: return B19200;
        case 38400: return B38400;
        case 57600: return B57600;
        case 115200: return B115200;
        case 230400: return B230400;
        case 460800: return B460800;
        case 500000: return B500000;
        case 921600: return B921600;
        case 1000000: return B1000000;
        default: return B0;
    }
}

[[noreturn]] void fail(const SerialSettings& s, const std::string& step, int err) {
    throw SerialError("serial port " + s.device + ": " + step + ": " + std::strerror(err));
}

}  // namespace

void SerialPort::open(const SerialSettings& s) {
    close();
    const int fd = ::open(s.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) fail(s, "open", errno);
    try {
        if (s.exclusive && ::ioctl(fd, TIOCEXCL) != 0) fail(s, "exclusive access (TIOCEXCL)", errno);
        termios t{};
        if (::tcgetattr(fd, &t) != 0) fail(s, "not a terminal (tcgetattr)", errno);
        ::cfmakeraw(&t);
        t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
        t.c_cflag |= CS8 | CLOCAL | CREAD;
        if (s.hangup_on_close) {
            t.c_cflag |= HUPCL;
        } else {
            t.c_cflag &= ~static_cast<tcflag_t>(HUPCL);
        }
        t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
        t.c_cc[VMIN] = 1;  // with O_NONBLOCK: EAGAIN when empty; 0 would read as end of file
        t.c_cc[VTIME] = 0;
        const speed_t speed = standard_speed(s.baud_rate);
        if (speed != B0) {
            ::cfsetispeed(&t, speed);
            ::cfsetospeed(&t, speed);
        }
        if (::tcsetattr(fd, TCSANOW, &t) != 0) fail(s, "configure (tcsetattr)", errno);
        if (speed == B0 && !set_custom_baud(fd, s.baud_rate))
            fail(s, "set custom baud rate " + std::to_string(s.baud_rate) + " (termios2 BOTHER)",
                 errno);
        ::tcflush(fd, TCIOFLUSH);  // stale bytes from before the open
        stream_.assign(fd);
    } catch (...) {
        ::close(fd);
        throw;
    }
    set_dtr(true);
}

void SerialPort::close() {
    if (!stream_.is_open()) return;
    boost::system::error_code ec;
    stream_.cancel(ec);
    stream_.close(ec);
}

bool SerialPort::set_dtr(bool on) {
    if (!stream_.is_open()) return false;
    int bits = TIOCM_DTR;
    return ::ioctl(stream_.native_handle(), on ? TIOCMBIS : TIOCMBIC, &bits) == 0;
}

}  // namespace fibrecell::drivers::marlin
