// The fibrecell-simcell program: started as a child process, it prints its ports, answers an RWS
// login with the configured user and a Modbus link, and exits cleanly on SIGTERM.
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/rws/rws_client.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

using namespace std::chrono_literals;
namespace abb = fibrecell::drivers::abb;
namespace rws = abb::rws;

namespace {

const std::string binary =
    std::string(FIBRECELL_BINARY_DIR) + "/tools/fibrecell-simcell/fibrecell-simcell";

// The program as a child with its stdout and stderr on pipes; killed if still running at the end.
class Child {
  public:
    explicit Child(std::vector<std::string> args) {
        int out[2], err[2];
        if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0)
            throw std::runtime_error("pipe");
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, out[1], 1);
        posix_spawn_file_actions_adddup2(&actions, err[1], 2);
        args.insert(args.begin(), binary);
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        const int rc = posix_spawn(&pid_, binary.c_str(), &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        close(out[1]);
        close(err[1]);
        out_ = out[0];
        err_ = err[0];
        if (rc != 0) throw std::runtime_error("cannot start " + binary);
    }
    ~Child() {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
        close(out_);
        close(err_);
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    // The next line of stdout, or nothing when none comes within `timeout`.
    std::optional<std::string> read_line(std::chrono::milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            if (const auto nl = out_buf_.find('\n'); nl != std::string::npos) {
                std::string line = out_buf_.substr(0, nl);
                out_buf_.erase(0, nl + 1);
                return line;
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left <= 0ms) return std::nullopt;
            pollfd p{out_, POLLIN, 0};
            if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
            char buf[256];
            const ssize_t n = read(out_, buf, sizeof buf);
            if (n <= 0) return std::nullopt;
            out_buf_.append(buf, static_cast<std::size_t>(n));
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
        if (!fibrecell::test::eventually([&] { return waitpid(pid_, &status, WNOHANG) == pid_; }, timeout, 5ms))
            return -1;
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }

  private:
    pid_t pid_ = -1;
    int out_ = -1, err_ = -1;
    std::string out_buf_;
};

struct Ports {
    std::uint16_t rws = 0;
    int modbus = 0;
};

// "fibrecell-simcell: rws=<port> modbus=<port>"
std::optional<Ports> parse_ready(const std::string& line) {
    static const std::regex ready(R"(fibrecell-simcell: rws=(\d+) modbus=(\d+))");
    std::smatch m;
    if (!std::regex_match(line, m, ready)) return std::nullopt;
    return Ports{static_cast<std::uint16_t>(std::stoi(m[1])), std::stoi(m[2])};
}

}  // namespace

TEST(SimCellTool, PrintsItsPortsAnswersRwsAndModbusAndStopsOnSigterm) {
    Child c({"--time-scale", "20", "--log-level", "warn"});
    const std::optional<std::string> line = c.read_line(10000ms);
    ASSERT_TRUE(line) << c.read_stderr();
    const std::optional<Ports> ports = parse_ready(*line);
    ASSERT_TRUE(ports) << *line;

    rws::RwsClient client({.host = "127.0.0.1", .port = ports->rws});
    const std::vector<rws::ModuleInfo> modules = client.modules();
    ASSERT_EQ(modules.size(), 1u);
    EXPECT_EQ(modules[0].name, "FcMain");
    EXPECT_EQ(client.execution_state().state, rws::ExecutionState::stopped);

    abb::RobotIoConfig io;
    io.port = ports->modbus;
    io.stats_log_period = std::chrono::seconds(0);
    abb::RobotIoLink link(io);
    link.start();
    EXPECT_TRUE(link.wait_until_up(3000ms)) << link.snapshot().last_error;
    link.stop();

    c.signal(SIGTERM);
    EXPECT_EQ(c.wait(5000ms), 0);
}

TEST(SimCellTool, TakesTheRwsUserFromTheCellConfigAndRejectsAWrongPassword) {
    const fibrecell::test::TempDir dir("simcell-tool");
    const auto cfg = dir.write("cell.yaml", "rws:\n  user: fibrecell\n  password: s3cret\n"
                                            "robot_io:\n  stable_reads: 1\n");
    Child c({"--config", cfg.string(), "--time-scale", "20", "--start"});
    const std::optional<std::string> line = c.read_line(10000ms);
    ASSERT_TRUE(line) << c.read_stderr();
    const std::optional<Ports> ports = parse_ready(*line);
    ASSERT_TRUE(ports) << *line;

    rws::RwsClient right(
        {.host = "127.0.0.1", .port = ports->rws, .user = "fibrecell", .password = "s3cret"});
    EXPECT_EQ(right.execution_state().state, rws::ExecutionState::running);  // --start
    rws::RwsClient wrong(
        {.host = "127.0.0.1", .port = ports->rws, .user = "fibrecell", .password = "robotics"});
    try {
        wrong.modules();
        FAIL() << "expected an authentication error";
    } catch (const rws::RwsError& e) {
        EXPECT_EQ(e.kind(), rws::RwsErrorKind::auth) << e.what();
    }
    c.signal(SIGINT);
    EXPECT_EQ(c.wait(5000ms), 0);
}

TEST(SimCellTool, ABadConfigKeyIsNamedAndTheProgramExits) {
    const fibrecell::test::TempDir dir("simcell-tool");
    const auto cfg = dir.write("cell.yaml", "robot_io:\n  poll_period_ms: 0\n");
    Child c({"--config", cfg.string()});
    EXPECT_EQ(c.wait(10000ms), 1);
    const std::string err = c.read_stderr();
    EXPECT_NE(err.find("poll_period_ms"), std::string::npos) << err;
}
