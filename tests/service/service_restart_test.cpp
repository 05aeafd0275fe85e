// Restart safety with the binaries as on a cell: the simulated IRC5 (fibrecell-simcell) and the
// mock GT2560 (mock-gt2560, logging every command it runs) are processes of their own, like the
// real devices, and fibrecelld drives them through its real drivers. The service is killed with
// SIGKILL in the middle of the print and started again: the job comes back interrupted with its
// last confirmed event, resumes at the start of the interrupted unit and completes, and neither
// the journal nor the board's log shows anything before the re-entry done twice.
#include "service_fixture.hpp"

#include <gmock/gmock.h>

#include <cstdio>
#include <set>

using namespace fibrecell;
using namespace fibrecell::test;

namespace {

constexpr double time_scale = 10;

struct Journal {
    std::vector<std::int64_t> before_resume, after_resume;  // confirmed sequences per run
    std::int64_t resume_first_event = 0;
};

Journal read_journal(const fs::path& p) {
    Journal j;
    std::ifstream in(p);
    std::string line;
    while (std::getline(in, line)) {
        const json r = json::parse(line);
        if (r.value("phase", "") == "resume") j.resume_first_event = r.value("first_event", std::int64_t{0});
        if (r.value("phase", "") != "confirmed") continue;
        (j.resume_first_event ? j.after_resume : j.before_resume).push_back(r.value("seq", std::int64_t{0}));
    }
    return j;
}

}  // namespace

TEST_F(ServiceTest, KilledMidPrintTheJobComesBackInterruptedAndResumesWithoutRepeats) {
    const std::string bin = FIBRECELL_BINARY_DIR;
    const fs::path board_log = dir_ / "board.log";
    ChildProcess board(bin + "/tools/mock-gt2560",
                       {"--daemon", "--link", (dir_ / "ttyGT2560").string(), "--time-scale",
                        std::to_string(time_scale), "--bootloader-s", "0.2", "--hotend-tau-s", "2",
                        "--residency-s", "0.5", "--log", board_log.string()},
                       dir_ / "mock.log");
    ASSERT_TRUE(board.wait_for_log("port ", 10s)) << board.log();
    ChildProcess robot(bin + "/tools/fibrecell-simcell/fibrecell-simcell",
                       {"--time-scale", std::to_string(time_scale)}, dir_ / "simcell.log");
    ASSERT_TRUE(robot.wait_for_log("modbus=", 20s)) << robot.log();
    // "fibrecell-simcell: rws=<port> modbus=<port>" (no std::regex: GCC 12 -O2 + ASan warns in it)
    const std::string banner = robot.log();
    const auto ports_at = banner.find("rws=");
    ASSERT_NE(ports_at, std::string::npos) << banner;
    int rws_port = 0, modbus_port = 0;
    ASSERT_EQ(std::sscanf(banner.c_str() + ports_at, "rws=%d modbus=%d", &rws_port, &modbus_port), 2)
        << banner;
    const std::string extra = "extruder: {link: {port: " + (dir_ / "ttyGT2560").string() + "}}\n" +
                              "rws: {port: " + std::to_string(rws_port) + "}\n" +
                              "print: {heartbeat_timeout_s: 1}\n";
    std::string config_text = read_file(write_config(extra, time_scale));
    const auto replace = [&](const std::string& from, const std::string& to) {
        const auto pos = config_text.find(from);
        ASSERT_NE(pos, std::string::npos) << from;
        config_text.replace(pos, from.size(), to);
    };
    replace("robot_io: {stable_reads: 1}", "robot_io: {stable_reads: 1, port: " + std::to_string(modbus_port) + "}");
    replace("residency_s: 0.5}", "residency_s: 0.5, devices: external}");
    std::ofstream(dir_ / "cell.yaml") << config_text;

    start_service(dir_ / "cell.yaml");
    std::int64_t id = 0;
    std::int64_t events = 0;
    {
        auto c = client();
        id = submit_bar(c, true);
        ASSERT_EQ(wait_for_state(c, id, "printing", 120s).value("state", ""), "printing") << service_->log();
        // Well into the print, then the plug is pulled.
        json job;
        const auto end = std::chrono::steady_clock::now() + 120s;
        do {
            job = c.call("job.get", {{"job", id}});
            std::this_thread::sleep_for(20ms);
        } while (job.value("last_confirmed_event", std::int64_t{0}) < 12 && std::chrono::steady_clock::now() < end);
        events = job["print"].value("events", std::int64_t{0});
        ASSERT_GE(job.value("last_confirmed_event", std::int64_t{0}), 12) << job.dump(2);
    }
    service_->kill_now();

    start_service(dir_ / "cell.yaml");
    auto c = client();
    const json interrupted = c.call("job.get", {{"job", id}});
    ASSERT_EQ(interrupted.value("state", ""), "interrupted") << interrupted.dump(2);
    const auto last = interrupted.value("last_confirmed_event", std::int64_t{0});
    EXPECT_GE(last, 12);
    ASSERT_EQ(c.call("job.resume", {{"job", id}}).value("state", ""), "starting");
    const json done = wait_for_state(c, id, "completed", 180s);
    ASSERT_EQ(done.value("state", ""), "completed") << done.dump(2) << "\n" << service_->log();

    // The journal: the first run confirmed 1..last in order; the resumed run re-entered at or
    // before last + 1 and confirmed every event from there to the end, once.
    const Journal j = read_journal(state_dir() / "jobs" / std::to_string(id) / "journal.jsonl");
    ASSERT_GT(j.resume_first_event, 0);
    EXPECT_LE(j.resume_first_event, last + 1);
    for (std::size_t i = 0; i < j.before_resume.size(); ++i)
        EXPECT_EQ(j.before_resume[i], static_cast<std::int64_t>(i) + 1);
    ASSERT_FALSE(j.after_resume.empty());
    EXPECT_EQ(j.after_resume.front(), j.resume_first_event);
    EXPECT_EQ(j.after_resume.back(), events);
    for (std::size_t i = 1; i < j.after_resume.size(); ++i)
        EXPECT_GT(j.after_resume[i], j.after_resume[i - 1]);
    // Nothing before the re-entered unit was done again.
    for (std::int64_t s : j.after_resume) EXPECT_GE(s, j.resume_first_event);

    // The board: the fibre threaded once per fibre path, plus at most the re-entered one.
    const std::string log = read_file(board_log);
    std::size_t threads = 0, cuts = 0;
    for (std::size_t at = 0; (at = log.find("M42 P11 S255", at)) != std::string::npos; ++at) ++cuts;
    for (std::size_t at = 0; (at = log.find("G1 E42.00000", at)) != std::string::npos; ++at) ++threads;
    EXPECT_LE(threads, cuts + 1);
    EXPECT_TRUE(service_->terminate(20s));
}
