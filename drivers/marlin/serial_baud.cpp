// termios2 lives in <asm/termbits.h>, which clashes with glibc's <termios.h>: this translation
// unit includes only the kernel header.
#include <asm/ioctls.h>
#include <asm/termbits.h>

extern "C" int ioctl(int fd, unsigned long request, ...) noexcept;

namespace fibrecell::drivers::marlin {

bool set_custom_baud(int fd, int baud_rate) {
    termios2 tio{};
    if (ioctl(fd, TCGETS2, &tio) != 0) return false;
    tio.c_cflag &= ~static_cast<tcflag_t>(CBAUD);
    tio.c_cflag |= BOTHER;
    tio.c_ispeed = static_cast<speed_t>(baud_rate);
    tio.c_ospeed = static_cast<speed_t>(baud_rate);
    return ioctl(fd, TCSETS2, &tio) == 0;
}

}  // namespace fibrecell::drivers::marlin
