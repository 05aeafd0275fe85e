// The fibrecell-simcell program: started as a child process, it prints its ports, answers an RWS
// login with the configured user and a Modbus link, and exits cleanly on SIGTERM.
#include "drivers/abb/modbus/robot_io_link.hpp"
#include "drivers/abb/rws/rws_client.hpp"
#include "tests/support/piped_process.hpp"
#include "tests/support/eventually.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

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

#include <unistd.h>

// Its own namespace: compiled in a batch with the other simulator tests, whose helpers share names.
namespace sim_simcell_tool_test {

using namespace std::chrono_literals;
namespace abb = fibrecell::drivers::abb;
namespace rws = abb::rws;

namespace {

const std::string binary =
    fibrecell::test::binary_path("tools/fibrecell-simcell/fibrecell-simcell");

// The program as a child process.
class Child : public fibrecell::test::PipedProcess {
  public:
    explicit Child(std::vector<std::string> args) : PipedProcess(binary, std::move(args)) {}
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

}  // namespace sim_simcell_tool_test
