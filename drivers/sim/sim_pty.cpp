#include "drivers/sim/sim_pty.hpp"

#include <cerrno>
#include <system_error>

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

namespace fibrecell::drivers::sim {

SimPty::SimPty(std::string link_path) : link_path_(std::move(link_path)) {}

SimPty::~SimPty() { close(); }

void SimPty::open() {
    close();
    int slave = -1;
    char name[128] = {};
    if (::openpty(&master_, &slave, name, nullptr, nullptr) != 0)
        throw std::system_error(errno, std::generic_category(), "simulated board: openpty");
    termios t{};
    ::tcgetattr(slave, &t);
    ::cfmakeraw(&t);  // no echo of the board's own output back into the master
    ::tcsetattr(slave, TCSANOW, &t);
    ::close(slave);   // the port reads as "closed" (POLLHUP) until the driver opens it
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    slave_name_ = name;
    if (!link_path_.empty()) {
        ::unlink(link_path_.c_str());
        if (::symlink(slave_name_.c_str(), link_path_.c_str()) != 0)
            throw std::system_error(errno, std::generic_category(),
                                    "simulated board: symlink " + link_path_);
    }
}

void SimPty::close() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
    if (!link_path_.empty()) ::unlink(link_path_.c_str());
}

}  // namespace fibrecell::drivers::sim
