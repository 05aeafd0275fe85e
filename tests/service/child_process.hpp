#pragma once
// A program of this build run as a child process for the service tests: its stdout and stderr go
// to a log file (read back for messages and errors), SIGTERM or SIGKILL on request, reaped and
// killed at the end at the latest.
#include "tests/support/eventually.hpp"
#include "tests/support/spawn.hpp"
#include "tests/support/temp_dir.hpp"

#include <chrono>
#include <csignal>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fibrecell::test {

class ChildProcess {
  public:
    // With `piped_stdin` the child reads what send_line() writes; else its stdin is /dev/null.
    ChildProcess(const std::string& program, std::vector<std::string> args, std::filesystem::path log,
                 bool piped_stdin = false)
        : log_(std::move(log)) {
        const int fd = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (fd < 0) throw std::runtime_error("cannot open " + log_.string());
        int in[2] = {-1, -1};
        if (piped_stdin && ::pipe2(in, O_CLOEXEC) != 0) throw std::runtime_error("cannot make a pipe");
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, fd, 1);
        posix_spawn_file_actions_adddup2(&actions, fd, 2);
        if (piped_stdin)
            posix_spawn_file_actions_adddup2(&actions, in[0], 0);
        else
            posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        pid_ = spawn_program(program, std::move(args), actions);
        posix_spawn_file_actions_destroy(&actions);
        ::close(fd);
        if (piped_stdin) {
            ::close(in[0]);
            stdin_ = in[1];
        }
        if (pid_ < 0) throw std::runtime_error("cannot start " + program);
    }
    ~ChildProcess() {
        kill_now();
        if (stdin_ >= 0) ::close(stdin_);
    }
    // One line to the child's stdin (piped_stdin only); false when it could not be written.
    bool send_line(const std::string& text) {
        const std::string line = text + "\n";
        return stdin_ >= 0 && ::write(stdin_, line.data(), line.size()) ==
                                  static_cast<ssize_t>(line.size());
    }
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    pid_t pid() const { return pid_; }
    bool running() {
        if (pid_ <= 0) return false;
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
            exit_status_ = status;
            pid_ = -1;
            return false;
        }
        return true;
    }
    // SIGKILL: as a crash or a power loss would end it.
    void kill_now() {
        if (pid_ <= 0) return;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &exit_status_, 0);
        pid_ = -1;
    }
    // SIGTERM, then waits; true when it exited by itself within `timeout`.
    bool terminate(std::chrono::milliseconds timeout) {
        if (pid_ <= 0) return true;
        ::kill(pid_, SIGTERM);
        if (eventually([&] { return !running(); }, timeout, std::chrono::milliseconds(10))) return true;
        kill_now();
        return false;
    }
    int exit_status() const { return exit_status_; }

    std::string log() const { return read_file(log_); }
    // Waits until the log contains `text`; false after `timeout` or when the child ended.
    bool wait_for_log(const std::string& text, std::chrono::milliseconds timeout) {
        bool ended = false;
        const auto found = [&] { return log().find(text) != std::string::npos; };
        return eventually([&] { return found() || (ended = !running()); }, timeout,
                          std::chrono::milliseconds(10)) &&
               (!ended || found());
    }

  private:
    std::filesystem::path log_;
    pid_t pid_ = -1;
    int exit_status_ = 0;
    int stdin_ = -1;
};

}  // namespace fibrecell::test
