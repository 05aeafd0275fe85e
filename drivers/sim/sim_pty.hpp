#pragma once
// The host side of a simulated board's USB serial port: a pseudo-terminal whose slave the driver
// opens like /dev/ttyUSB0, optionally behind a stable symlink that survives an unplug/replug.

#include <string>

namespace fibrecell::drivers::sim {

class SimPty {
  public:
    // `link_path` may be empty (the driver is then given slave_name()).
    explicit SimPty(std::string link_path = {});
    ~SimPty();
    SimPty(const SimPty&) = delete;
    SimPty& operator=(const SimPty&) = delete;

    // A new pty in raw mode, master non-blocking, the symlink pointed at it. Throws
    // std::system_error naming the step that failed.
    void open();
    // Closes the master (the driver reads EOF/EIO, as on a cable pull) and removes the symlink.
    void close();

    int master() const { return master_; }
    std::string slave_name() const { return slave_name_; }
    // The path for the driver: the symlink when there is one, else /dev/pts/N.
    std::string port_path() const { return link_path_.empty() ? slave_name_ : link_path_; }

  private:
    std::string link_path_;
    std::string slave_name_;
    int master_ = -1;
};

}  // namespace fibrecell::drivers::sim
