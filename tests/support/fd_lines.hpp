#pragma once
// Lines from a file descriptor (a child's stdout, a pseudo-terminal) with a deadline: the line is
// the event a test waits for.

#include <chrono>
#include <optional>
#include <string>

#include <poll.h>
#include <unistd.h>

namespace fibrecell::test {

class FdLines {
  public:
    explicit FdLines(int fd = -1) : fd_(fd) {}

    // The next line without its '\n', or nothing within `timeout` (or once the other end closed).
    std::optional<std::string> next(std::chrono::milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            if (const auto nl = buf_.find('\n'); nl != std::string::npos) {
                std::string line = buf_.substr(0, nl);
                buf_.erase(0, nl + 1);
                return line;
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left <= std::chrono::milliseconds(0)) return std::nullopt;
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
            char b[4096];
            const ssize_t n = ::read(fd_, b, sizeof b);
            if (n <= 0) return std::nullopt;
            buf_.append(b, static_cast<std::size_t>(n));
        }
    }

  private:
    int fd_;
    std::string buf_;
};

}  // namespace fibrecell::test
