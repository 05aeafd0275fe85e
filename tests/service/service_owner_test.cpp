// One owner per state directory, with fibrecelld as its users run it: a second service on the same
// state directory (another socket) refuses to start naming the first, which goes on untouched;
// a state or socket directory that others may write to is refused before anything is read or
// created in it.
#include "service_fixture.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>

#include <sys/stat.h>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

// Runs fibrecelld with `args` until it exits by itself; its exit code, or -1 if it kept running.
int exit_code_of(const std::vector<std::string>& args, const fs::path& log, std::string& out) {
    ChildProcess p(fibrecell::test::binary_path("daemon/fibrecelld"), args, log);
    const bool ended = eventually([&] { return !p.running(); }, 30s, 10ms);
    out = p.log();
    return ended && WIFEXITED(p.exit_status()) ? WEXITSTATUS(p.exit_status()) : -1;
}

}  // namespace

TEST_F(ServiceTest, ASecondServiceOnTheSameStateDirectoryRefusesToStart) {
    const fs::path config = write_config();
    start_service(config);
    auto c = client();
    const std::int64_t id = submit_bar(c, false);
    const json before = wait_for_state(c, id, "planned");
    ASSERT_EQ(before.value("state", ""), "planned") << before.dump();

    std::string out;
    const int code = exit_code_of({"--config", config.string(), "--socket",
                                   (dir_ / "second.sock").string()},
                                  dir_ / "second.log", out);
    EXPECT_EQ(code, 2) << out;
    EXPECT_THAT(out, HasSubstr(state_dir().string() + " is in use by fibrecelld pid " +
                               std::to_string(service_->pid()) + " (socket " + socket().string() +
                               ")"));
    EXPECT_FALSE(fs::exists(dir_ / "second.sock"));
    // The first goes on: it answers, and its job is as it was.
    EXPECT_EQ(c.call("job.get", {{"job", id}}).value("state", ""), "planned");
    EXPECT_TRUE(service_->running());
}

TEST_F(ServiceTest, AStateDirectoryOthersMayWriteToIsRefused) {
    fs::create_directories(state_dir());
    ::chmod(state_dir().c_str(), 0777);
    std::string out;
    EXPECT_EQ(exit_code_of({"--config", write_config().string()}, dir_ / "refused.log", out), 2);
    EXPECT_THAT(out, HasSubstr("state directory " + state_dir().string() + " has mode 0777"));
    EXPECT_FALSE(fs::exists(state_dir() / "jobs"));  // nothing made in it
}

TEST_F(ServiceTest, ASocketDirectoryOthersMayWriteToIsRefused) {
    const fs::path open_dir = dir_ / "open";
    fs::create_directories(open_dir);
    ::chmod(open_dir.c_str(), 0777);
    std::string out;
    EXPECT_EQ(exit_code_of({"--config", write_config().string(), "--socket",
                            (open_dir / "api.sock").string()},
                           dir_ / "refused.log", out),
              2);
    EXPECT_THAT(out, HasSubstr("socket directory " + open_dir.string() + " has mode 0777"));
    EXPECT_FALSE(fs::exists(open_dir / "api.sock"));
}
