// Soak (label `soak`, outside the default suite: `ctest -L soak`): 50 prints back to back on one
// simulated cell, every driver real, with random faults. The mock board corrupts, drops or
// duplicates about 1% of the numbered lines of every print; every fifth print also loses the
// robot's Modbus link in the middle of a fibre path and is resumed as an operator would.
//   * A print with board faults only runs exactly the planned board log: nothing lost, nothing
//     repeated (the link's resends make the faults invisible to the firmware).
//   * A print that faulted feeds every path's planned feed once: what the board fed plus what
//     the engine accounts as left at the cut or the extrude_off is the plan's, to 1e-4 mm.
//   * Memory stays flat: the process's RSS after the 50th print is within 16 MiB of the 10th
//     (not checked under AddressSanitizer, whose quarantine grows by design).
// FIBRECELL_SOAK_PRINTS and FIBRECELL_SOAK_SEED override the count and the random seed.
#include "print_cell_fixture.hpp"

#include <gmock/gmock.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>

using namespace fibrecell;
using namespace fibrecell::test;

namespace {

long rss_kib() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}

int env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v ? std::atoi(v) : fallback;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool sanitized = true;
#else
constexpr bool sanitized = false;
#endif
#else
constexpr bool sanitized = false;
#endif

// The E fed with each tool, from the board's executed lines (T0 PLA, T1 fibre; the fibre's
// threads of `thread_mm` left out, the PLA's primes and retracts cancel out).
struct Fed {
    double pla_mm = 0, fibre_mm = 0;
};

Fed fed_by_tool(const std::vector<std::string>& log, double thread_mm) {
    Fed f;
    bool fibre = false;
    for (const std::string& l : log) {
        if (l == "T0") fibre = false;
        if (l == "T1") fibre = true;
        if (l.rfind("G1 E", 0) != 0) continue;
        const double e = std::stod(l.substr(4));
        if (fibre && std::abs(e - thread_mm) > 1e-9) f.fibre_mm += e;
        if (!fibre) f.pla_mm += e;
    }
    return f;
}

// The simulated robot keeps the service's default trajectory record (10,000 samples), not the
// whole path other tests measure along: the memory figure is then the cell's, not the record's.
class PrintSoakTest : public PrintCellTest {
  protected:
    PrintSoakTest() { trajectory_samples_ = 10'000; }
};

}  // namespace

TEST_F(PrintSoakTest, FiftyPrintsWithRandomFaultsLoseAndRepeatNothing) {
    const int prints = env_int("FIBRECELL_SOAK_PRINTS", 50);
    const auto seed = static_cast<unsigned>(env_int("FIBRECELL_SOAK_SEED", 17));
    std::mt19937 rng(seed);
    const abb::PrintProgram program = make_program({pla_square(0, 0.8), fibre_lines(1, 0.85, 2)});
    const auto expected = expected_board_log(program);
    const Fed planned = fed_by_tool(expected, 42);
    const auto lines = static_cast<std::int64_t>(expected.size());
    std::printf("soak: %d prints, seed %u, %lld board lines each\n", prints, seed,
                static_cast<long long>(lines));
    long rss_10 = 0, rss_last = 0;
    const int baseline = std::min(10, prints);
    std::uint64_t faults_injected = 0, resumes = 0;
    for (int i = 1; i <= prints; ++i) {
        SCOPED_TRACE("print " + std::to_string(i));
        job_start_ = mock().executed_count();
        const std::int64_t first = *mock().executed().back().line + 1;
        std::uniform_int_distribution<std::int64_t> line(first + 3, first + lines - 1);
        std::uniform_int_distribution<int> kind(0, 2);
        for (std::int64_t n = 0; n < lines / 100 + 1; ++n, ++faults_injected) {
            const std::int64_t k = line(rng);
            switch (kind(rng)) {
                case 0: mock().corrupt_line(k); break;
                case 1: mock().drop_line(k); break;
                default: mock().duplicate_line(k); break;
            }
        }
        const bool robot_fault = i % 5 == 0;
        make_session(program, chunks_of(program), options());
        session_->start();
        if (robot_fault) {
            const auto fibre = first_of(program, EventKind::fibre_start);
            ASSERT_TRUE(metering(fibre, std::uniform_int_distribution<std::size_t>(2, 40)(rng)));
            cell().drop_modbus_link(800ms);
            ASSERT_TRUE(eventually([&] { return session_->poll().phase == PrintPhase::faulted; }))
                << "phase " << daemon::print::to_string(session_->poll().phase);
            ASSERT_TRUE(robot().wait_until_up(10s));
            ASSERT_TRUE(eventually([&] {
                try {
                    session_->resume();
                    return true;
                } catch (const daemon::print::PrintError&) {
                    return false;  // the robot program not held yet
                }
            }, 20s, 100ms));
            ++resumes;
        }
        ASSERT_EQ(session_->wait_until_done(120s), PrintPhase::completed) << session_->poll().reason;
        const auto log = executed_job();
        if (!robot_fault) {
            ASSERT_EQ(log, expected);
        } else {
            const auto stats = session_->poll().sync.stats;
            const Fed fed = fed_by_tool(log, 42);
            EXPECT_NEAR(fed.fibre_mm + stats.feed_left_at_cut_mm, planned.fibre_mm, 1e-4);
            EXPECT_NEAR(fed.pla_mm + stats.extrusion_left_at_off_mm, planned.pla_mm, 1e-4);
        }
        if (i == baseline) rss_10 = rss_kib();
        rss_last = rss_kib();
    }
    std::printf("soak: %d prints done, %llu board faults injected, %llu robot link faults resumed, "
                "%llu resend requests; VmRSS %ld KiB after print %d, %ld KiB after the last\n",
                prints, static_cast<unsigned long long>(faults_injected),
                static_cast<unsigned long long>(resumes),
                static_cast<unsigned long long>(board().stats().resend_requests), rss_10, baseline,
                rss_last);
    if (!sanitized) {
        EXPECT_LT(rss_last - rss_10, 16 * 1024);
    }
}
