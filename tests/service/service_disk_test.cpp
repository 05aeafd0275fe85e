// A full disk in the middle of a print, with fibrecelld as its users run it: the state directory
// is a small tmpfs, filled while the job prints. The journal write fails, the cell goes safe, the
// job pauses with the reason, and the service goes on answering; with space again the job is
// aborted as usual, and the journal holds whole lines only. Needs root to mount the tmpfs
// (skipped otherwise).
#include "service_fixture.hpp"

#include <gmock/gmock.h>

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <sstream>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

// A tmpfs of `size` at `dir` for the object's life; detached lazily (the service may hold it).
class SmallDisk {
  public:
    SmallDisk(const fs::path& dir, const std::string& size) : dir_(dir) {
        fs::create_directories(dir);
        const std::string options = "size=" + size + ",mode=0750";
        if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) != 0)
            error_ = std::strerror(errno);
    }
    ~SmallDisk() {
        if (error_.empty()) ::umount2(dir_.c_str(), MNT_DETACH);
    }
    const std::string& error() const { return error_; }

  private:
    fs::path dir_;
    std::string error_;
};

// Writes `file` until the disk is full.
void fill(const fs::path& file) {
    std::ofstream out(file, std::ios::binary);
    const std::string block(64 * 1024, 'x');
    while (out.write(block.data(), static_cast<std::streamsize>(block.size())) && out.flush()) {
    }
}

}  // namespace

TEST_F(ServiceTest, AFullDiskMidPrintHoldsTheCellAndKeepsTheServiceAnswering) {
    if (::geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
    SmallDisk disk(state_dir(), "8m");
    if (!disk.error().empty()) GTEST_SKIP() << "cannot mount a tmpfs: " << disk.error();
    start_service(write_config("", 5));
    auto c = client();
    const std::int64_t id = submit_bar(c, true);
    const fs::path journal = state_dir() / "jobs" / std::to_string(id) / "journal.jsonl";
    ASSERT_TRUE(eventually([&] { return fs::exists(journal) && fs::file_size(journal) > 0; }, 120s))
        << c.call("job.get", {{"job", id}}).dump();

    fill(state_dir() / "filler");
    const json paused = wait_for_state(c, id, "paused", 60s);
    ASSERT_EQ(paused.value("state", ""), "paused") << paused.dump(2) << service_->log();
    EXPECT_THAT(paused.value("reason", ""), HasSubstr("No space left on device"));
    EXPECT_TRUE(service_->running());
    const json cell = c.call("cell.status");  // still answering
    EXPECT_TRUE(cell.is_object());
    // A job submitted meanwhile is refused as the other writes are, -32005, and nothing of it
    // is left behind.
    const std::size_t jobs_before = c.call("job.list").size();
    try {
        c.call("job.submit", submit_params(dir_ / "jobs/bar.job.yaml", "bar.vtk", false), 30s);
        ADD_FAILURE() << "a job was stored on a full disk";
    } catch (const api::ApiCallError& e) {
        EXPECT_EQ(e.code(), -32005) << e.what();
        EXPECT_THAT(e.what(), HasSubstr("No space left on device"));
    }
    EXPECT_EQ(c.call("job.list").size(), jobs_before);

    fs::remove(state_dir() / "filler");
    c.call("job.abort", {{"job", id}});
    const json aborted = wait_for_state(c, id, "aborted", 60s);
    EXPECT_EQ(aborted.value("state", ""), "aborted") << aborted.dump(2);
    const json disk_state = json::parse(
        read_file(state_dir() / "jobs" / std::to_string(id) / "state.json"), nullptr, false);
    EXPECT_EQ(disk_state.value("state", ""), "aborted");  // saved once there was room

    // Whole lines only: a write the full disk cut short was taken back.
    const std::string text = read_file(journal);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.back(), '\n');
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        EXPECT_FALSE(json::parse(line, nullptr, false).is_discarded()) << "torn: " << line;
}
