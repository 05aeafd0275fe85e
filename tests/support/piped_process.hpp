#pragma once
// One of the project's programs run as a child process, its stdin, stdout and stderr on pipes;
// killed if it is still running when the object goes. Tests read its output line by line with a
// deadline (the line is the event they wait for).

#include "tests/support/eventually.hpp"
#include "tests/support/fd_lines.hpp"
#include "tests/support/spawn.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fibrecell::test {

class PipedProcess {
  public:
    PipedProcess(const std::string& program, std::vector<std::string> args) {
        int in[2], out[2], err[2];
        if (pipe2(in, O_CLOEXEC) != 0 || pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0)
            throw std::runtime_error("pipe");
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, in[0], 0);
        posix_spawn_file_actions_adddup2(&actions, out[1], 1);
        posix_spawn_file_actions_adddup2(&actions, err[1], 2);
        pid_ = spawn_program(program, std::move(args), actions);
        posix_spawn_file_actions_destroy(&actions);
        close(in[0]);
        close(out[1]);
        close(err[1]);
        in_ = in[1];
        out_ = FdLines(out[0]);
        out_fd_ = out[0];
        err_ = err[0];
        if (pid_ < 0) throw std::runtime_error("cannot start " + program);
    }
    ~PipedProcess() {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
        close(in_);
        close(out_fd_);
        close(err_);
    }
    PipedProcess(const PipedProcess&) = delete;
    PipedProcess& operator=(const PipedProcess&) = delete;

    // One line on the child's stdin.
    void write_line(const std::string& line) {
        const std::string l = line + "\n";
        if (::write(in_, l.data(), l.size()) != static_cast<ssize_t>(l.size()))
            throw std::runtime_error("cannot write to the child's stdin");
    }

    // The next line of stdout, or nothing when none comes within `timeout`.
    std::optional<std::string> read_line(std::chrono::milliseconds timeout) { return out_.next(timeout); }

    // The next stdout line that starts with `prefix`, the prefix taken off; other lines are
    // passed over (a library may print its own).
    std::optional<std::string> read_line_starting(const std::string& prefix,
                                                  std::chrono::milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            const auto line = read_line(std::max(left, std::chrono::milliseconds(0)));
            if (!line) return std::nullopt;
            if (line->rfind(prefix, 0) == 0) return line->substr(prefix.size());
        }
    }

    // Everything on stderr until the child closes it.
    std::string read_stderr() {
        std::string all;
        char buf[512];
        for (ssize_t n; (n = read(err_, buf, sizeof buf)) > 0;)
            all.append(buf, static_cast<std::size_t>(n));
        return all;
    }

    void signal(int sig) { kill(pid_, sig); }

    // The exit status (or 128 + signal); -1 when it does not exit within `timeout`.
    int wait(std::chrono::milliseconds timeout) {
        int status = 0;
        if (!eventually([&] { return waitpid(pid_, &status, WNOHANG) == pid_; }, timeout,
                        std::chrono::milliseconds(5)))
            return -1;
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }

  private:
    pid_t pid_ = -1;
    int in_ = -1, out_fd_ = -1, err_ = -1;
    FdLines out_;
};

}  // namespace fibrecell::test
