// The one durable writer: files replaced whole (a reader sees the old or the new content), no
// temporary left behind, unique temporary names per writer (two writers of one file never share
// one), missing folders made, and appends one line at a time, a cut-short one taken back.
#include "config/durable_file.hpp"

#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

using namespace fibrecell::config;
namespace fs = std::filesystem;

namespace {

std::size_t entries(const fs::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::recursive_directory_iterator(dir)) ++n;
    return n;
}

class DurableFileTest : public ::testing::Test {
  protected:
    fibrecell::test::TempDir tmp_{"durable"};
    const fs::path dir_ = tmp_.path();
};

}  // namespace

TEST_F(DurableFileTest, ReplacesAFileWholeAndLeavesNoTemporary) {
    write_file_durably(dir_ / "state.json", "one");
    write_file_durably(dir_ / "state.json", "two, longer");
    EXPECT_EQ(fibrecell::test::read_file(dir_ / "state.json"), "two, longer");
    EXPECT_EQ(entries(dir_), 1u);
    EXPECT_THROW(write_file_durably(dir_ / "missing" / "x", "y"), std::system_error);
}

TEST_F(DurableFileTest, ManyFilesCommittedTogetherInFoldersItMakes) {
    DurableFiles plan(dir_ / "plan");
    plan.write("toolpaths.json", "{}\n");
    plan.write("rapid/FcChunk0001.mod", "MODULE FcChunk0001\n");
    plan.write("preview/a/b/layer_0001.svg", "<svg/>");
    plan.write("toolpaths.json", "{\"v\": 2}\n");  // again: replaced
    plan.commit();
    EXPECT_EQ(fibrecell::test::read_file(dir_ / "plan" / "toolpaths.json"), "{\"v\": 2}\n");
    EXPECT_EQ(fibrecell::test::read_file(dir_ / "plan" / "rapid" / "FcChunk0001.mod"), "MODULE FcChunk0001\n");
    EXPECT_EQ(fibrecell::test::read_file(dir_ / "plan" / "preview" / "a" / "b" / "layer_0001.svg"), "<svg/>");
    for (const auto& e : fs::recursive_directory_iterator(dir_))
        EXPECT_FALSE(is_leftover_temp_file(e.path())) << e.path();
    EXPECT_EQ(entries(dir_ / "plan"), 7u);  // 3 files, 4 folders
}

TEST_F(DurableFileTest, WritersOfOneFileNeverShareATemporary) {
    // Two threads replace the same file many times: every read sees one writer's whole text.
    const std::string a(100000, 'a'), b(50000, 'b');
    std::vector<std::thread> writers;
    for (const std::string* text : {&a, &b})
        writers.emplace_back([&, text] {
            for (int i = 0; i < 50; ++i) write_file_durably(dir_ / "shared", *text);
        });
    for (int i = 0; i < 50; ++i) {
        const std::string now = fibrecell::test::read_file(dir_ / "shared");
        if (!now.empty()) {
            EXPECT_TRUE(now == a || now == b) << now.size() << " bytes";
        }
    }
    for (auto& t : writers) t.join();
    EXPECT_EQ(entries(dir_), 1u);
}

TEST_F(DurableFileTest, TemporaryNamesAreRecognised) {
    EXPECT_TRUE(is_leftover_temp_file(dir_ / "state.json.tmp-1234-7"));
    EXPECT_FALSE(is_leftover_temp_file(dir_ / "state.json"));
}

TEST_F(DurableFileTest, AppendsWholeLines) {
    {
        DurableAppender journal(dir_ / "journal.jsonl");
        journal.append("{\"seq\":1}");
        journal.append("{\"seq\":2}");
    }
    DurableAppender again(dir_ / "journal.jsonl");
    again.append("{\"seq\":3}");
    EXPECT_EQ(fibrecell::test::read_file(dir_ / "journal.jsonl"), "{\"seq\":1}\n{\"seq\":2}\n{\"seq\":3}\n");
}

TEST_F(DurableFileTest, AnAppendTheDiskCutsShortIsTakenBack) {
    // A child whose files may not grow past 100 bytes (RLIMIT_FSIZE: the write stops there as
    // on a full disk): the fourth 32-byte line is cut at byte 100, the append throws, and the
    // file keeps its three whole lines.
    const fs::path file = dir_ / "journal.jsonl";
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a kill
        const rlimit limit{100, 100};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(2);
        DurableAppender journal(file);
        const std::string line(31, 'a');
        for (int i = 0; i < 4; ++i) {
            try {
                journal.append(line);
            } catch (const std::system_error&) {
                ::_exit(i == 3 ? 0 : 3);
            }
        }
        ::_exit(1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    ASSERT_EQ(WEXITSTATUS(status), 0) << "1: nothing failed, 2: no limit, 3: failed too soon";
    const std::string line(31, 'a');
    EXPECT_EQ(fibrecell::test::read_file(file), line + "\n" + line + "\n" + line + "\n");
}
