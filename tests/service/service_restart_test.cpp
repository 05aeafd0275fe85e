// Restart safety with the binaries as on a cell: the simulated IRC5 (fibrecell-simcell) and the
// mock GT2560 (mock-gt2560, logging every command it runs) are processes of their own, like the
// real devices, and fibrecelld drives them through its real drivers. The service is killed with
// SIGKILL in the middle of the print and started again (within FcMain's heartbeat timeout, as
// systemd restarts it, or after: the robot stops either way): the job comes back interrupted
// with its last confirmed event, resumes in the interrupted fibre path (the fibre in the part
// cut, the rest laid from where its recorded feed ended) and completes; neither the journal nor
// the board's log shows anything done twice, and the fibre the board fed is the plan's plus one
// re-thread. The
// simulated robot's recorded trajectory shows the resumed run lift straight up from where it
// stopped.
#include "external_cell.hpp"
#include "service_fixture.hpp"

#include <gmock/gmock.h>

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <map>
#include <sstream>
#include <utility>
#include <set>
#include <thread>
#include <vector>

using namespace fibrecell;
using namespace fibrecell::test;

namespace {

// Simulated seconds per real second of the kill test.
constexpr double restart_time_scale = 20;
// The other test of this file: the service stopped, not killed.
constexpr double stopped_time_scale = 10;

struct Journal {
    std::vector<std::int64_t> before_resume, after_resume;  // confirmed sequences per run
    std::int64_t resume_first_event = 0;
};

// A row of fibrecell-simcell's --trajectory CSV.
struct TrajectoryRow {
    double t_s = 0, x = 0, y = 0, z = 0, path = 0, speed = 0;
    std::uint64_t segment = 0;
};

std::vector<TrajectoryRow> read_trajectory(const fs::path& p) {
    std::vector<TrajectoryRow> rows;
    std::ifstream in(p);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        TrajectoryRow r;
        unsigned long long segment = 0;
        if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%llu", &r.t_s, &r.x, &r.y, &r.z,
                        &r.path, &r.speed, &segment) != 7)
            break;  // a row being written
        r.segment = segment;
        rows.push_back(r);
    }
    return rows;
}

// Rows recorded up to the robot's stop after the kill: the robot program reports it no longer
// runs, and the file (rows are added while the robot moves) ends with the robot's standstill. 0
// when the robot did not stop within 30 s.
std::size_t rows_when_held(api::ApiClient& c, const fs::path& p) {
    std::size_t rows = 0;
    const bool held = eventually([&] {
        const std::vector<TrajectoryRow> t = read_trajectory(p);
        rows = t.size();
        return !t.empty() && t.back().speed == 0 &&
               !c.call("cell.status")["robot"].value("running", true);
    }, 30s, 50ms);
    return held ? rows : 0;
}

// The journal's last confirmed event is a fibre start numbered `at_least` or later.
bool laying_fibre_after(const fs::path& p, std::int64_t at_least) {
    std::ifstream in(p);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find("\"confirmed\"") != std::string::npos && line.back() == '}') last = line;
    if (last.empty()) return false;
    const json r = json::parse(last);
    return r.value("kind", "") == "fibre_start" && r.value("seq", std::int64_t{0}) >= at_least;
}

// The journal's last `fed` record: {fibre_start, mm}; {0, 0} when none.
std::pair<std::int64_t, double> last_fed(const fs::path& p) {
    std::ifstream in(p);
    std::string line;
    std::pair<std::int64_t, double> fed{0, 0};
    while (std::getline(in, line)) {
        if (line.find("\"fed\"") == std::string::npos || line.back() != '}') continue;
        const json r = json::parse(line);
        fed = {r.value("seq", std::int64_t{0}), r.value("mm", 0.0)};
    }
    return fed;
}

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
    ExternalCell devices(dir_, restart_time_scale);
    ASSERT_TRUE(devices.up());
    const fs::path& board_log = devices.board_log();
    const fs::path& trajectory = devices.trajectory();
    std::ofstream(dir_ / "cell.yaml")
        << devices.cell_yaml(read_file(write_config("", restart_time_scale)),
                             "print: {heartbeat_timeout_s: 0.5}\n");

    start_service(dir_ / "cell.yaml");
    std::int64_t id = 0;
    std::int64_t events = 0;
    {
        auto c = client();
        id = submit_bar(c, true);
        ASSERT_EQ(wait_for_state(c, id, "printing", 120s).value("state", ""), "printing") << service_->log();
        events = c.call("job.get", {{"job", id}})["print"].value("events", std::int64_t{0});
        // Well into the print, with the robot laying a fibre (threaded, moving along the path,
        // at least 10 mm fed and 30 mm left before the cut: the journal's lag behind the board,
        // a poll of 0.1 s, is 10 mm at 20x): then the plug is pulled.
        const fs::path journal = state_dir() / "jobs" / std::to_string(id) / "journal.jsonl";
        const auto planned = planned_events(state_dir() / "jobs" / std::to_string(id) / "plan" / "program.json");
        ASSERT_TRUE(eventually([&] {
            if (!laying_fibre_after(journal, 12)) return false;
            const auto [seq, mm] = last_fed(journal);
            const auto e = planned.find(seq);
            // The record is of the path being laid: its fibre_start is the last event confirmed.
            return e != planned.end() && laying_fibre_after(journal, seq) &&
                   !laying_fibre_after(journal, seq + 1) && mm >= 10 && mm <= e->second.length_mm - 30;
        }, 120s, 2ms)) << read_file(journal);
    }
    service_->kill_now();
    const fs::path journal = state_dir() / "jobs" / std::to_string(id) / "journal.jsonl";
    const auto [interrupted_path, fed_before] = last_fed(journal);
    std::printf("killed with %.1f mm fed along the fibre path of event %lld\n", fed_before,
                static_cast<long long>(interrupted_path));

    start_service(dir_ / "cell.yaml");
    auto c = client();
    const json interrupted = c.call("job.get", {{"job", id}});
    ASSERT_EQ(interrupted.value("state", ""), "interrupted") << interrupted.dump(2);
    const auto last = interrupted.value("last_confirmed_event", std::int64_t{0});
    EXPECT_GE(last, 12);
    const std::size_t held_rows = rows_when_held(c, trajectory);
    ASSERT_GT(held_rows, 0u) << "the robot did not stop after the kill: "
                             << c.call("cell.status")["robot"].dump() << "\n" << devices.robot_log();
    std::printf("the robot stopped: %s\n",
                service_->log().find("cell.orphan_run") != std::string::npos
                    ? "its run aborted by the restarted service (back within the heartbeat timeout)"
                    : "held by FcMain on the lost heartbeat");
    ASSERT_EQ(c.call("job.resume", {{"job", id}}).value("state", ""), "starting");
    const json done = wait_for_state(c, id, "completed", 180s);
    ASSERT_TRUE(printed(done)) << done.dump(2) << "\n" << service_->log();

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

    // The board: the fibre threaded once per fibre path and once more for the rest of the
    // interrupted one, which was cut before the lift: as many threads as cuts.
    const std::string log = read_file(board_log);
    std::size_t threads = 0, cuts = 0;
    for (std::size_t at = 0; (at = log.find("M42 P11 S255", at)) != std::string::npos; ++at) ++cuts;
    for (std::size_t at = 0; (at = log.find("G1 E42.00000", at)) != std::string::npos; ++at) ++threads;
    EXPECT_EQ(threads, cuts);
    // Fibre fed = planned (each path's feed up to its cut and its 42 mm thread) plus the one
    // re-thread, within what the journal's last record lagged behind the board (a poll, 0.1 s:
    // 10 mm of path at 20x) and the board's queue lost to the reset when the port reopened.
    double planned_mm = 0;
    for (const auto& [seq, e] : planned_events(state_dir() / "jobs" / std::to_string(id) / "plan" / "program.json"))
        if (e.kind == "fibre_start") planned_mm += e.length_mm + 42;
    const double fed_mm = devices.board_fed()[1];
    if (std::getenv("FIBRECELL_TEST_SHOW_LOG")) std::printf("%s\n", service_->log().c_str());
    std::printf("fibre fed %.1f mm, planned %.1f mm, one re-thread 42 mm: %+.1f mm\n", fed_mm,
                planned_mm, fed_mm - planned_mm - 42);
    EXPECT_NEAR(fed_mm, planned_mm + 42, 10) << "fed before the kill: " << fed_before << " mm";

    // The robot: the resumed run's first motion is the lift, straight up by the travel clearance
    // (5 mm) from where the robot was held; the next one leaves that height upwards or level.
    const std::vector<TrajectoryRow> rows = read_trajectory(trajectory);
    ASSERT_GT(rows.size(), held_rows);
    const std::vector<TrajectoryRow> resumed(rows.begin() + static_cast<std::ptrdiff_t>(held_rows), rows.end());
    const auto first_moving = std::find_if(resumed.begin(), resumed.end(), [](const auto& r) { return r.speed > 0; });
    ASSERT_NE(first_moving, resumed.end());
    ASSERT_NE(first_moving, resumed.begin());
    const TrajectoryRow held = *std::prev(first_moving);
    std::vector<TrajectoryRow> lift;
    for (auto it = first_moving; it != resumed.end() && it->segment == first_moving->segment; ++it) lift.push_back(*it);
    ASSERT_GE(lift.size(), 3u);
    for (std::size_t i = 0; i < lift.size(); ++i) {
        EXPECT_NEAR(lift[i].x, lift.front().x, 2e-4) << "lift row " << i;
        EXPECT_NEAR(lift[i].y, lift.front().y, 2e-4) << "lift row " << i;
        if (i > 0) {
            EXPECT_GT(lift[i].z, lift[i - 1].z) << "lift row " << i;
        }
    }
    EXPECT_NEAR(lift.back().path - held.path, 5, 1e-3);
    std::printf("held at bed (%.3f, %.3f, %.3f) mm; lifted to z %.3f mm\n", held.x, held.y, held.z,
                lift.back().z);
    EXPECT_EQ(lift.back().speed, 0);  // a stop point
    EXPECT_TRUE(service_->terminate(20s));
}

// Stopped (SIGSTOP) mid-print, the service's heartbeat to the robot stops and FcMain holds the
// robot; continued, the service says that it was itself stopped, not that the robot was lost.
TEST_F(ServiceTest, AServiceThatWasStoppedMidPrintSaysSoWhenItRunsAgain) {
    start_service(write_config("", stopped_time_scale));
    auto c = client();
    const std::int64_t id = submit_bar(c, true);
    ASSERT_EQ(wait_for_state(c, id, "printing", 120s).value("state", ""), "printing") << service_->log();
    ASSERT_EQ(::kill(service_->pid(), SIGSTOP), 0);
    std::this_thread::sleep_for(3s);  // the stop itself is the event: three heartbeat timeouts
    ASSERT_EQ(::kill(service_->pid(), SIGCONT), 0);
    const json paused = wait_for_state(c, id, "paused", 30s);
    ASSERT_EQ(paused.value("state", ""), "paused") << paused.dump(2) << service_->log();
    EXPECT_THAT(paused.value("reason", ""), ::testing::HasSubstr("fibrecelld itself did not run for"));
    EXPECT_THAT(paused.value("reason", ""), ::testing::Not(::testing::HasSubstr("robot heartbeat lost")));
    EXPECT_EQ(c.call("job.abort", {{"job", id}}).value("state", ""), "aborted");
}
