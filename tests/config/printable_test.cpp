// User text made safe for logs and terminals (config/printable.hpp), and the service's log
// formatter that applies it to every line: a name with a newline or an escape sequence can
// neither forge a log line nor move the cursor.
#include "config/logging.hpp"
#include "config/printable.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <unistd.h>

using fibrecell::config::printable;

TEST(Printable, ControlCharactersBecomeVisibleEscapes) {
    EXPECT_EQ(printable("bar\n2026-12-02T07:00:00.000 info job.completed"),
              "bar\\n2026-12-02T07:00:00.000 info job.completed");
    EXPECT_EQ(printable("\x1b[2Kgone"), "\\x1b[2Kgone");
    EXPECT_EQ(printable(std::string("a\0b\r\t\x7f", 6)), "a\\x00b\\r\\t\\x7f");
}

TEST(Printable, OtherTextIsKeptAsItIs) {
    EXPECT_EQ(printable("Träger 15° – ok"), "Träger 15° – ok");  // UTF-8 bytes are >= 0x80
    EXPECT_EQ(printable(""), "");
}

TEST(Printable, EveryLogLineIsOneLine) {
    fibrecell::test::TempDir tmp("printable");
    const auto file = tmp / "stderr.txt";
    const int saved = ::dup(2);
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ASSERT_GE(fd, 0);
    ::dup2(fd, 2);
    fibrecell::config::setup_logging("info");
    spdlog::info("job.submitted name={}", "bar\n2026-12-02T07:00:00.000 info job.completed\x1b[2K");
    spdlog::default_logger()->flush();
    ::dup2(saved, 2);
    ::close(fd);
    ::close(saved);
    const std::string log = fibrecell::test::read_file(file);
    ASSERT_FALSE(log.empty());
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
    EXPECT_NE(log.find("name=bar\\n2026-12-02T07:00:00.000 info job.completed\\x1b[2K"),
              std::string::npos)
        << log;
}
