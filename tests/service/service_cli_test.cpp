// The `fibrecell` client against a running fibrecelld (service_fixture.hpp): submit --start
// --watch follows a job to its outcome, jobs and status in both output forms, and one clear line
// with a non-zero exit code for every error (no service, a conflict).
#include "service_fixture.hpp"
#include "tests/support/project_paths.hpp"

#include <gmock/gmock.h>

#include <algorithm>
#include <pwd.h>
#include <unistd.h>
#include <array>
#include <cstdio>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

struct CliRun {
    int status = -1;
    std::string out;
};

// Runs a program of this build with `args`; stdout and stderr together.
CliRun fibrecell_cli_program(const std::string& program, const std::string& args) {
    const std::string cmd = fibrecell::test::binary_path(program) + " " + args + " 2>&1";
    CliRun r;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 512> buf{};
    while (fgets(buf.data(), buf.size(), p)) r.out += buf.data();
    const int s = pclose(p);
    r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
    return r;
}

// Runs the client with `args`.
CliRun fibrecell_cli(const std::string& args) { return fibrecell_cli_program("tools/fibrecell", args); }

}  // namespace

TEST_F(ServiceTest, TheClientSaysClearlyWhenTheServiceIsNotRunning) {
    const CliRun r = fibrecell_cli("status --socket " + socket().string());
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "fibrecell: fibrecelld is not running (no socket at " + socket().string() + ")\n");
}

// Both programs and the running service name the same build: its version and the commit of its
// sources (a bug report, a history record).
TEST_F(ServiceTest, TheProgramsAndTheServiceNameTheirBuild) {
    start_service(write_config());
    const json info = client().call("server.info");
    const std::string build = info.value("version", "") + " (commit " + info.value("commit", "") + ")";
    EXPECT_THAT(info.value("commit", ""), ::testing::MatchesRegex("[0-9a-f]{7,}(-dirty)?|unknown"));
    const CliRun client_version = fibrecell_cli("--version");
    EXPECT_EQ(client_version.status, 0);
    EXPECT_EQ(client_version.out, "fibrecell " + build + "\n");
    const CliRun service_version = fibrecell_cli_program("daemon/fibrecelld", "--version");
    EXPECT_EQ(service_version.status, 0);
    EXPECT_EQ(service_version.out, "fibrecelld " + build + "\n");
}

TEST_F(ServiceTest, SubmitStartWatchFollowsTheJobToItsOutcome) {
    start_service(write_config());
    const std::string sock = " --socket " + socket().string();
    const CliRun watched = fibrecell_cli("submit " + (dir_ / "jobs/bar.job.yaml").string() + " --start --watch" + sock);
    // A test of the client's flow, not of the print's quality: on a busy machine the print may
    // end completed_with_warnings (a shortfall of half a millimetre), and then `watch` says so and
    // exits 1 (0 only for completed).
    const bool warned = watched.out.find("completed_with_warnings") != std::string::npos;
    const std::string outcome = warned ? "completed_with_warnings" : "completed";
    EXPECT_EQ(watched.status, warned ? 1 : 0) << watched.out;
    EXPECT_THAT(watched.out, HasSubstr("job 1 (bar) submitted: planning, prints when planned"));
    EXPECT_THAT(watched.out, HasSubstr("job 1: printing"));
    EXPECT_THAT(watched.out, HasSubstr("job 1 (bar) " + outcome + ": "));
    EXPECT_THAT(watched.out, HasSubstr("job folder  " + (state_dir() / "jobs/1").string()));

    const CliRun jobs = fibrecell_cli("jobs" + sock);
    EXPECT_EQ(jobs.status, 0);
    EXPECT_THAT(jobs.out, HasSubstr("   1  bar                  " + outcome));
    const CliRun as_json = fibrecell_cli("jobs --json" + sock);
    const json parsed = json::parse(as_json.out);
    ASSERT_EQ(parsed.size(), 1u);
    EXPECT_EQ(parsed[0]["state"], outcome);
    const CliRun status = fibrecell_cli("status" + sock);
    EXPECT_THAT(status.out, HasSubstr("cell test-cell (simulated)"));
    // The heaters went off with the print's end (within a poll of the print runner).
    EXPECT_TRUE(eventually([&] {
        return fibrecell_cli("status" + sock).out.find("heaters: off (job 1 completed)") != std::string::npos;
    }, 10s, 200ms)) << fibrecell_cli("status" + sock).out;

    const CliRun conflict = fibrecell_cli("pause" + sock);
    EXPECT_EQ(conflict.status, 1);
    EXPECT_EQ(conflict.out, "fibrecell: job.pause: no job is on the cell; name one\n");
    const CliRun finished = fibrecell_cli("start 1" + sock);
    EXPECT_EQ(finished.status, 1);
    EXPECT_THAT(finished.out, HasSubstr("fibrecell: job 1 is completed"));

    // Job 1's part is on the bed (docs/queue.md): the next job plans, is not started, and the
    // watch says why instead of waiting for a start that will not come.
    EXPECT_THAT(fibrecell_cli("status" + sock).out, HasSubstr("bed:    not clear: job 1 (bar) " + outcome));
    const CliRun held = fibrecell_cli("submit " + (dir_ / "jobs/bar.job.yaml").string() + " --start --watch" + sock);
    EXPECT_EQ(held.status, 1) << held.out;
    EXPECT_THAT(held.out, HasSubstr("job 2 planned; not started: job 2 cannot start: the cell is not "
                                    "clear: job 1's part (" + outcome + " at "));

    // The operator takes the part off and says so; the cell prints the next job as well (the
    // previous run's outputs are reset for it).
    const CliRun cleared = fibrecell_cli("clear" + sock);
    EXPECT_EQ(cleared.status, 0) << cleared.out;
    EXPECT_THAT(cleared.out, HasSubstr("cell cleared\nbed: clear\n"));
    EXPECT_EQ(fibrecell_cli("start 2" + sock).status, 0);
    const CliRun second = fibrecell_cli("watch 2" + sock);
    const bool second_warned = second.out.find("completed_with_warnings") != std::string::npos;
    EXPECT_EQ(second.status, second_warned ? 1 : 0) << second.out;
    EXPECT_THAT(second.out, HasSubstr(second_warned ? "job 2 (bar) completed_with_warnings: "
                                                    : "job 2 (bar) completed: "));

    // The history of both, as a table and as CSV (docs/history.md).
    EXPECT_TRUE(eventually([&] {
        return fibrecell_cli("history --json" + sock).out.find("\"count\":2") != std::string::npos;
    }, 10s, 100ms)) << fibrecell_cli("history --json" + sock).out;
    const CliRun history = fibrecell_cli("history" + sock);
    EXPECT_EQ(history.status, 0);
    const passwd* me = ::getpwuid(::getuid());  // the socket's user started them
    EXPECT_THAT(history.out, HasSubstr(std::string("bar (") + (me ? me->pw_name : "uid") ));
    const CliRun csv = fibrecell_cli("history --csv" + sock);
    EXPECT_EQ(csv.status, 0);
    EXPECT_EQ(csv.out.rfind("id,name,strategy,outcome,", 0), 0u) << csv.out;
    EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 3) << csv.out;
    EXPECT_EQ(json::parse(fibrecell_cli("history --json --since 2999-01-01" + sock).out).value("count", -1), 0);
    const CliRun bad_date = fibrecell_cli("history --since yesterday" + sock);
    EXPECT_EQ(bad_date.status, 1);
    EXPECT_THAT(bad_date.out, HasSubstr("params.since"));

    // A spool, its length with a unit; without one, or below zero, refused (docs/spools.md).
    const CliRun loaded = fibrecell_cli("spool load T1 --material \"CF 1K\" --length 250m --lot A17" + sock);
    EXPECT_EQ(loaded.status, 0) << loaded.out;
    EXPECT_THAT(loaded.out, HasSubstr("T1 (fibre): CF 1K, lot A17: 250.00 m left of 250.00 m"));
    const json spools = json::parse(fibrecell_cli("spool --json" + sock).out);
    EXPECT_DOUBLE_EQ(spools["spools"][1].value("remaining_m", 0.0), 250.0);
    const CliRun no_unit = fibrecell_cli("spool load T0 --material PLA --length 250" + sock);
    EXPECT_EQ(no_unit.status, 1);
    EXPECT_THAT(no_unit.out, HasSubstr("length '250' needs a unit: mm, m, km"));
    const CliRun negative = fibrecell_cli("spool load T0 --material PLA --length=-3m" + sock);
    EXPECT_EQ(negative.status, 1);
    EXPECT_THAT(negative.out, HasSubstr("must be more than 0"));
}

// A start the cell refuses (here the extruder board's port is not there) sends the job back to
// planned with the reason: `submit --start --watch` ends there, with the reason and exit 1,
// instead of watching a planned job for ever.
TEST_F(ServiceTest, SubmitStartWatchEndsWhenTheStartIsRefused) {
    std::string text = with_board_port(
        read_file(write_config("print: {connect_timeout_s: 1}\n", /*time_scale=*/1)),  // an external board: real time
        dir_ / "no-such-tty");
    const std::string from = "residency_s: 0.5}";
    text.replace(text.find(from), from.size(), "residency_s: 0.5, board: external}");
    std::ofstream(dir_ / "cell.yaml") << text;
    start_service(dir_ / "cell.yaml");
    const std::string sock = " --socket " + socket().string();
    const CliRun watched =
        fibrecell_cli("submit " + (dir_ / "jobs/bar.job.yaml").string() + " --start --watch" + sock);
    EXPECT_EQ(watched.status, 1) << watched.out;
    EXPECT_THAT(watched.out, HasSubstr("job 1: starting"));
    EXPECT_THAT(watched.out, HasSubstr("job 1: planned ("));
    EXPECT_THAT(watched.out, HasSubstr("no-such-tty"));
}
