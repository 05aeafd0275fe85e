// Owning a directory (config/directory_owner.hpp): a missing state directory is created 0750; one
// that others may write to, or that another user owns, is refused with its path, owner or mode;
// /tmp-like sticky directories pass; one lock per directory, released by the kernel when its
// holder dies (kill -9 included), the refusal naming the holder.
#include "config/directory_owner.hpp"
#include "tests/support/temp_dir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <optional>

using namespace fibrecell;
using fibrecell::test::TempDir;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

mode_t mode_of(const fs::path& p) {
    struct stat st {};
    ::stat(p.c_str(), &st);
    return st.st_mode & 07777;
}

std::string refusal(const fs::path& dir) {
    try {
        config::ensure_private_directory(dir, "state directory");
    } catch (const config::DirectoryRefused& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PrivateDirectory, AMissingOneIsCreatedForItsOwnerAndGroupOnly) {
    TempDir tmp("owner");
    const fs::path dir = tmp / "a" / "state";
    config::ensure_private_directory(dir, "state directory");
    ASSERT_TRUE(fs::is_directory(dir));
    EXPECT_EQ(mode_of(dir) & 0027, 0u) << std::oct << mode_of(dir);  // 0750 less the umask
    config::ensure_private_directory(dir, "state directory");  // and accepted again
}

TEST(PrivateDirectory, OneOthersMayWriteToIsRefusedWithItsMode) {
    TempDir tmp("owner");
    const fs::path dir = tmp / "state";
    fs::create_directory(dir);
    ::chmod(dir.c_str(), 0777);
    EXPECT_THAT(refusal(dir), HasSubstr("state directory " + dir.string() + " has mode 0777"));
    ::chmod(dir.c_str(), 0770);
    EXPECT_THAT(refusal(dir), HasSubstr("others may write to it"));
    ::chmod(dir.c_str(), 0750);
    EXPECT_EQ(refusal(dir), "");
}

TEST(PrivateDirectory, AStickyDirectoryAsTmpPasses) {
    TempDir tmp("owner");
    const fs::path dir = tmp / "shared";
    fs::create_directory(dir);
    ::chmod(dir.c_str(), 01777);
    EXPECT_EQ(refusal(dir), "");
}

TEST(PrivateDirectory, OneAnotherUserOwnsIsRefused) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to give a directory to another user";
    TempDir tmp("owner");
    const fs::path dir = tmp / "state";
    fs::create_directory(dir);
    ::chmod(dir.c_str(), 0750);
    ASSERT_EQ(::chown(dir.c_str(), 12345, 12345), 0);
    EXPECT_THAT(refusal(dir), HasSubstr("belongs to uid 12345"));
}

TEST(PrivateDirectory, AFileIsNotADirectory) {
    TempDir tmp("owner");
    std::ofstream(tmp / "file") << "x";
    EXPECT_THAT(refusal(tmp / "file"), HasSubstr("is not a directory"));
}

TEST(DirectoryLock, ASecondHolderIsRefusedNamingTheFirst) {
    TempDir tmp("lock");
    std::optional<config::DirectoryLock> first;
    first.emplace(tmp.path(), "fibrecelld pid 1 (socket /run/a.sock)");
    try {
        config::DirectoryLock second(tmp.path(), "fibrecelld pid 2");
        FAIL() << "a second lock was granted";
    } catch (const config::DirectoryRefused& e) {
        EXPECT_THAT(e.what(), HasSubstr(tmp.string() + " is in use by fibrecelld pid 1 (socket "
                                        "/run/a.sock): one service per state directory"));
    }
    first.reset();
    config::DirectoryLock again(tmp.path(), "fibrecelld pid 3");  // released with its holder
}

TEST(DirectoryLock, AHolderKilledWithSigkillLeavesNoStaleLock) {
    TempDir tmp("lock");
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        config::DirectoryLock lock(tmp.path(), "the child");
        const char ok = 1;
        if (::write(ready[1], &ok, 1) != 1) ::_exit(1);
        ::pause();
        ::_exit(0);
    }
    char ok = 0;
    ASSERT_EQ(::read(ready[0], &ok, 1), 1);
    EXPECT_THROW(config::DirectoryLock(tmp.path(), "the parent"), config::DirectoryRefused);
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    ::close(ready[0]);
    ::close(ready[1]);
    EXPECT_NO_THROW(config::DirectoryLock(tmp.path(), "the parent"));
    EXPECT_TRUE(fs::exists(tmp / "fibrecelld.lock"));  // the file stays; its lock went
}
