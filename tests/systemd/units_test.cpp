// The systemd units as configured by the build: `systemd-analyze verify` accepts them (with
// ExecStart pointed at the built fibrecelld, since the install paths do not exist here), they are
// Type=notify with a watchdog, and the template unit gives each cell its own config, state and
// socket. Skipped where systemd-analyze is not installed.
#include "tests/support/temp_dir.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs a shell command; returns its exit status and output (stdout and stderr).
std::pair<int, std::string> run(const std::string& cmd) {
    std::string out;
    FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    if (!p) return {-1, "popen failed"};
    std::array<char, 512> buf{};
    while (fgets(buf.data(), buf.size(), p)) out += buf.data();
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

class SystemdUnitTest : public ::testing::Test {
  protected:
    void SetUp() override {
        units_ = fs::path(fibrecell::test::binary_path("systemd"));
    }

    // The unit with its ExecStart binary replaced by the built one, written as `name` in dir_.
    fs::path testable(const std::string& unit, const std::string& name) {
        std::string text = read(units_ / unit);
        const std::string built = fibrecell::test::binary_path("daemon/fibrecelld");
        text = std::regex_replace(text, std::regex("ExecStart=\\S+/fibrecelld"), "ExecStart=" + built);
        std::ofstream(dir_ / name) << text;
        return dir_ / name;
    }

    fs::path units_;
    fibrecell::test::TempDir dir_{"units"};
};

}  // namespace

TEST_F(SystemdUnitTest, TheServiceUnitIsNotifyWithAWatchdogAndASandbox) {
    const std::string unit = read(units_ / "fibrecelld.service");
    ASSERT_FALSE(unit.empty()) << "no configured unit in " << units_;
    for (const char* line : {"Type=notify", "WatchdogSec=", "Restart=on-failure", "StateDirectory=fibrecelld",
                             "RuntimeDirectory=fibrecelld", "User=fibrecell", "SupplementaryGroups=dialout",
                             "DeviceAllow=char-ttyUSB rw", "ProtectSystem=strict",
                             "ExecReload=/bin/kill -HUP $MAINPID"})
        EXPECT_THAT(unit, HasSubstr(line));
    EXPECT_FALSE(std::regex_search(unit, std::regex("@[A-Z_]+@"))) << "unconfigured @VAR@";
}

TEST_F(SystemdUnitTest, TheTemplateGivesEachCellItsOwnConfigStateAndSocket) {
    const std::string unit = read(units_ / "fibrecelld@.service");
    EXPECT_THAT(unit, HasSubstr("/%i.yaml --state-dir /var/lib/fibrecelld/%i --socket /run/fibrecelld/%i/api.sock"));
    EXPECT_THAT(unit, HasSubstr("StateDirectory=fibrecelld/%i"));
    EXPECT_THAT(unit, HasSubstr("RuntimeDirectory=fibrecelld/%i"));
}

TEST_F(SystemdUnitTest, SystemdAnalyzeVerifiesBothUnits) {
    if (run("command -v systemd-analyze").first != 0) GTEST_SKIP() << "systemd-analyze not installed";
    if (!fs::exists(fs::path(fibrecell::test::binary_path("daemon/fibrecelld"))))
        GTEST_SKIP() << "fibrecelld not built";
    const auto service = testable("fibrecelld.service", "fibrecelld.service");
    const auto [rc, out] = run("systemd-analyze verify " + service.string());
    EXPECT_EQ(rc, 0) << out;
    EXPECT_THAT(out, ::testing::Not(HasSubstr("fibrecelld.service:"))) << out;
    const auto instance = testable("fibrecelld@.service", "fibrecelld@cell2.service");
    const auto [rc2, out2] = run("systemd-analyze verify " + instance.string());
    EXPECT_EQ(rc2, 0) << out2;
    EXPECT_THAT(out2, ::testing::Not(HasSubstr("fibrecelld@cell2.service:"))) << out2;
}
