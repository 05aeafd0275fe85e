// A print through a GT2560 running firmware: fibrecelld with the simulated robot in-process at
// time scale 1 (simulation.board: external) and the extruder board in gt2560-avr, running the
// project's test firmware (tests/firmware). Checked from the board's pins (tools/board-check,
// reading the plan's files and the edge log, not the service): every fibre and PLA path got its
// planned feed within 0.5%, as many cuts as planned, nothing lost or run twice, though the wire
// is faulty all along (1% of the host's lines corrupted) and the MCU stops for 2 s mid-print.
// Then the MCU resets in the middle of the last fibre path: the job holds with the board named,
// what the board had taken and not run is fed again, and the resume finishes it. One print for
// all of it: it takes over two minutes of real time.
#include "service_fixture.hpp"
#include "tests/support/piped_process.hpp"
#include "tools/board-check/board_check.hpp"
#include "tests/support/project_paths.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <deque>
#include <iomanip>
#include <sstream>
#include <iostream>

using namespace fibrecell;
using namespace fibrecell::test;

namespace {

const std::string board_tool = fibrecell::test::binary_path("tools/gt2560-avr");
const std::string firmware = fibrecell::test::binary_path("tests/firmware/gt2560-test-firmware.elf");

class AvrBoardPrint : public ServiceTest {
  protected:
    void SetUp() override {
        if (!fs::exists(board_tool) || !fs::exists(firmware))
            GTEST_SKIP() << "gt2560-avr or the test firmware is not built (libsimavr-dev, gcc-avr)";
        ServiceTest::SetUp();
        fs::copy(fibrecell::test::source_path("examples/strip"), dir_ / "strip");
        // Three and two times the example's print speeds (PLA 36 mm/s, CF 10 mm/s: still speeds
        // the heads lay at): the same events in about half the time; this test sets the suite's
        // floor.
        std::ofstream(dir_ / "strip/strip.job.yaml", std::ios::app)
            << "\nprocess:\n  pla: {speed_mm_s: 36}\n  ccf: {speed_mm_s: 10}\n";
        // Real-time heaters, quicker than a real hotend's: 25 -> 250 C in about 6 s.
        std::string text = with_board_port(read_file(write_config("", /*time_scale=*/1)), tty());
        const std::string from = "residency_s: 0.5}";
        text.replace(text.find(from), from.size(),
                     "residency_s: 0.5, board: external, heat_capacity_j_per_k: 1}");
        std::ofstream(dir_ / "cell.yaml") << text;
    }

    fs::path tty() const { return dir_ / "ttyGT2560"; }

    void start_board() {
        board_.emplace(board_tool, std::vector<std::string>{
                                       firmware, "--link", tty().string(), "--cell",
                                       (dir_ / "cell.yaml").string(), "--edge-log",
                                       (dir_ / "edges.log").string()});
        ASSERT_TRUE(board_->read_line_starting("port ", 20s)) << board_->read_stderr();
    }

    void board_command(const std::string& command) {
        board_->write_line(command);
        ASSERT_TRUE(board_->read_line_starting("done " + command.substr(0, command.find(' ')), 10s))
            << command;
    }

    json board_status() {
        board_->write_line("status");
        const auto status = board_->read_line_starting("status ", 10s);
        if (!status) throw std::runtime_error("no status from gt2560-avr");
        return json::parse(*status);
    }

    std::int64_t submit_strip(api::ApiClient& c) {
        return c.call("job.submit", submit_params(dir_ / "strip/strip.job.yaml", "strip.vtk", true), 30s)
            .value("id", std::int64_t{0});
    }

    std::optional<PipedProcess> board_;
};

}  // namespace

TEST_F(AvrBoardPrint, TheStripPrintsOnAFaultyWireAndAcrossAnMcuResetWithTheFeedsTheBoardWasGiven) {
    start_board();
    board_command("fault to-board line 0.01");
    start_service(dir_ / "cell.yaml");
    auto c = client();
    const std::int64_t id = submit_strip(c);
    ASSERT_GT(id, 0);
    // During the first fibre path (event 10 is its fibre_start), the board stops for 2 s.
    ASSERT_TRUE(eventually([&] {
        const json j = c.call("job.get", {{"job", id}});
        return j.contains("print") && j["print"].value("event", 0) >= 10;
    }, 300s)) << service_->log();
    board_command("pause 2");
    // 20 mm into the second fibre path's metered feed (after the first path's 199 mm and its own
    // 42 mm thread), the MCU resets.
    // The polls also keep how much real time the simulated MCU fell behind and wrote off (on a
    // busy machine), for the interrupted path's check below: over the whole of that path's feed,
    // since all the time written off while it was metered piles up in the board's queue (up to
    // its 4 moves), where the service, which models the board at its own real time, cannot see it.
    constexpr double path_start_mm = 198.96 + 42;
    constexpr double reset_at_mm = path_start_mm + 20;
    const auto fibre_mm = [](const json& status) { return status["extruders"][1]["mm"].get<double>(); };
    std::deque<std::pair<std::chrono::steady_clock::time_point, json>> polls;
    ASSERT_TRUE(eventually([&] {
        polls.emplace_back(std::chrono::steady_clock::now(), board_status());
        while (polls.size() > 2 && fibre_mm(polls[1].second) <= path_start_mm) polls.pop_front();
        return fibre_mm(polls.back().second) >= reset_at_mm;
    }, 300s, 100ms)) << service_->log();
    const auto reset_sent = std::chrono::system_clock::now();
    board_command("reset");
    const json at_reset = board_status();
    const json& before = polls.front().second;
    const double slip_s = at_reset["behind"]["written_off_s"].get<double>() -
                          before["behind"]["written_off_s"].get<double>();
    const double fibre_mm_s = (fibre_mm(polls.back().second) - fibre_mm(before)) /
                              std::max(1e-3, std::chrono::duration<double>(polls.back().first -
                                                                           polls.front().first).count());

    const json held = wait_for_state(c, id, "paused", 60s);
    ASSERT_EQ(held.value("state", ""), "paused") << held.dump(2) << service_->log();
    const auto reset_seen = logged_at(service_->log(), "extruder.link_fault reason=firmware_reset");
    ASSERT_TRUE(reset_seen) << service_->log();
    EXPECT_NE(held.value("reason", "").find("extruder board"), std::string::npos) << held.value("reason", "");
    // What the board had taken and not run at the reset is fed again on resume, and the reason
    // says so; a host running late (a busy machine) may have left nothing queued on the board
    // (seen in CI: the reset between two pieces), and then the reason says nothing of it.
    const bool taken_back = service_->log().find("sync.feed_lost_in_reset") != std::string::npos;
    std::printf("at the reset the board %s\n",
                taken_back ? "had feed it had taken and not run" : "had nothing queued");
    EXPECT_EQ(held.value("reason", "").find("fed again on resume") != std::string::npos, taken_back)
        << held.value("reason", "");
    ASSERT_EQ(c.call("job.resume", {{"job", id}}).value("state", ""), "printing") << service_->log();
    const json done = wait_for_state(c, id, "completed", 600s);
    ASSERT_TRUE(printed(done)) << done.dump(2) << service_->log();

    // From the pins (the status flushes the edge log).
    const json board = board_status();
    EXPECT_EQ(board["resets"], 1);
    EXPECT_GT(board["wire"]["to_board"].value("lines_corrupted", 0), 0);  // the faults were there
    std::cout << "wire: " << board["wire"].dump() << "\nresult: " << done.value("result", json{}).dump() << "\n";
    const auto r = tools::check_board((state_dir() / "jobs" / std::to_string(id) / "plan").string(),
                                      (dir_ / "edges.log").string());
    ASSERT_EQ(r.planned_pla_paths, 6);
    ASSERT_EQ(r.planned_fibre_paths, 2);
    ASSERT_EQ(r.paths.size(), 8u);
    // The resume in the same session meters the rest of the interrupted path without a cut (the
    // robot has not moved): as many cuts as planned.
    EXPECT_EQ(r.cuts, r.planned_cuts);
    // Before the reset, across corrupted lines and the pause, nothing lost or run twice: every
    // PLA path and the first fibre path within 0.5% of the plan.
    for (const auto& p : r.paths) {
        std::cout << p.kind << " layer " << p.layer << " path " << p.path << ": planned "
                  << p.planned_mm << " mm, fed " << p.fed_mm << " mm\n";
        if (!(p.kind == "fibre" && p.layer == 3)) {
            EXPECT_NEAR(p.fed_mm, p.planned_mm, 0.005 * p.planned_mm) << p.kind << " layer " << p.layer;
        }
    }
    // The interrupted path: what the firmware had acknowledged but not yet run when it reset was
    // lost with its queue; the service takes it off the fed amount by the board's feed rate and
    // feeds it again on resume. So the path is short by the feed the service reports as dropped
    // and no more than a model's error (0.02-0.3 mm seen; 0.9 to 3.9 mm when nothing was taken back).
    const auto& interrupted = r.paths[7];
    double reported = 0;
    for (const auto& f : done["result"].value("shortfalls", json::array())) reported += f.value("mm", 0.0);
    const double unknown = interrupted.planned_mm - reported - interrupted.fed_mm;
    // The service counts the board's queue in wall time from when it reads the firmware's
    // `start`: what ran between the reset and that line (a busy host reads it late) and real
    // time the simulated MCU wrote off just before the reset (a machine too busy to run it at
    // real time, which a real board never is) are unknown to it, at the feed rate each; and on
    // a loaded machine the times it read the board's `ok`s by have been off by up to 64 ms (at
    // 5 mm/s, 0.32 mm unaccounted for; with nothing taken back, 0.9 to 3.9 mm): 75 ms allowed.
    // A machine so busy that the MCU wrote off time is late reading the `ok`s too: in CI, with
    // 284 ms written off, 90 ms of them unaccounted for; a quarter of what was written off more.
    const double seen_after_s = std::max(0.0, std::chrono::duration<double>(*reset_seen - reset_sent).count());
    const double late_mm = (seen_after_s + 1.25 * slip_s + 0.075) * fibre_mm_s;
    std::printf("interrupted fibre path: planned %.3f mm, fed %.3f mm: %.3f mm reported as dropped, "
                "%.3f mm unaccounted for; allowed: 0.1 mm and, at %.2f mm/s, the reset seen "
                "%.1f ms after it was sent, 1.25 x %.1f ms written off by the MCU and 75 ms: %.3f mm\n",
                interrupted.planned_mm, interrupted.fed_mm, reported, unknown, fibre_mm_s,
                seen_after_s * 1e3, slip_s * 1e3, late_mm);
    EXPECT_NEAR(unknown, 0.0, 0.1 + late_mm);
}

// A hotend that cannot heat (a cartridge of 0.05 W) under the test firmware's heating watchdog
// (Marlin's rule, 2 C in 5 s in this build): the firmware halts during the heat-up, the start is
// refused with the firmware's own words, and `fibrecell submit --start --watch` ends on it within
// a second, exit 1. After a reset of the board the job starts again.
TEST_F(AvrBoardPrint, AWatchdogHaltDuringHeatUpRefusesTheStartWithTheFirmwaresErrorAndTheJobStaysStartable) {
    std::string text = read_file(dir_ / "cell.yaml");
    const std::string from = "heat_capacity_j_per_k: 1}";
    text.replace(text.find(from), from.size(), "heat_capacity_j_per_k: 1, heater_power_w: 0.05}");
    std::ofstream(dir_ / "cell.yaml") << text;
    start_board();
    start_service(dir_ / "cell.yaml");
    PipedProcess cli(fibrecell::test::binary_path("tools/fibrecell"),
                     {"submit", (dir_ / "strip/strip.job.yaml").string(), "--start", "--watch",
                      "--socket", socket().string()});
    const auto refused = cli.read_line_starting("job 1: planned (", 180s);
    ASSERT_TRUE(refused) << cli.read_stderr() << service_->log();
    EXPECT_NE(refused->find("Error:Heating failed, system stopped! Heater_ID: "), std::string::npos) << *refused;
    ASSERT_EQ(cli.wait(10s), 1);
    const auto exited = std::chrono::system_clock::now();
    const auto logged = logged_at(service_->log(), "print.start_refused");
    ASSERT_TRUE(logged) << service_->log();
    const double after_s = std::chrono::duration<double>(exited - *logged).count();
    std::printf("the watch ended %.0f ms after the service refused the start\n", after_s * 1e3);
    EXPECT_LT(after_s, 1.0);

    auto c = client();
    const json job = c.call("job.get", {{"job", 1}});
    EXPECT_EQ(job.value("state", ""), "planned");
    EXPECT_NE(job.value("reason", "").find("Heating failed"), std::string::npos) << job.dump(2);
    board_command("reset");
    // The board boots again; the service takes the start once it has the link back.
    std::string state;
    ASSERT_TRUE(eventually([&] {
        try {
            state = c.call("job.start", {{"job", 1}}).value("state", "");
            return true;
        } catch (const api::ApiCallError&) {
            return false;
        }
    }, 60s, 500ms)) << service_->log();
    EXPECT_EQ(state, "starting");
    // The same cartridge: refused again, for the same reason.
    const json again = wait_for_state(c, 1, "planned", 120s);
    EXPECT_NE(again.value("reason", "").find("Heating failed"), std::string::npos) << again.dump(2);
}
