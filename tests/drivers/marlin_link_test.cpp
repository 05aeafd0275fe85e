// The real MarlinLink against the mock GT2560 over a real pseudo-terminal.
#include "drivers/marlin/marlin_link.hpp"
#include "drivers/sim/mock_board/mock_gt2560.hpp"

#include "tests/support/eventually.hpp"
#include "tests/support/temp_dir.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <random>
#include <thread>

using namespace fibrecell::drivers;
using namespace fibrecell::drivers::marlin;
using namespace std::chrono_literals;
using fibrecell::test::eventually;
using fibrecell::test::TempDir;

namespace {

CommandOutcome finish(std::future<CommandOutcome> f, std::chrono::seconds limit = 30s) {
    if (f.wait_for(limit) != std::future_status::ready) return {LinkFailure::ack_timeout, "test: no result"};
    return f.get();
}

class MarlinLinkTest : public ::testing::Test {
  protected:
    void start(sim::MockGt2560Options mo = {}, MarlinLinkConfig lc = {}) {
        mo.link_path = (dir_ / "ttyGT2560").string();
        if (mo.bootloader_s == 1.0) mo.bootloader_s = 0.01 * mo.time_scale;  // 10 ms real
        mock_ = std::make_unique<sim::MockGt2560>(mo);
        lc.serial.device = mock_->port_path();
        config_ = lc;
        link_.configure(lc);
        link_.activate();
        job_start_ = mock_->executed_count();
    }
    void TearDown() override {
        if (link_.state() == DeviceState::active) link_.deactivate();
        mock_.reset();
    }
    // The commands the mock executed since the handshake, in order.
    std::vector<std::string> executed_job() const {
        std::vector<std::string> out;
        const auto log = mock_->executed();
        for (std::size_t i = job_start_; i < log.size(); ++i) out.push_back(log[i].text);
        return out;
    }
    void reconnect() {
        link_.clear();
        link_.configure(config_);
        link_.activate();
        job_start_ = mock_->executed_count();
    }

    TempDir dir_{"marlin-link"};  // first: the port's link in it outlives the mock
    std::unique_ptr<sim::MockGt2560> mock_;
    MarlinLink link_;
    MarlinLinkConfig config_;
    std::size_t job_start_ = 0;
};

std::vector<std::string> numbered_job(int n) {
    std::vector<std::string> job;
    for (int i = 0; i < n; ++i)
        job.push_back(i % 2 == 0 ? "G92 E" + std::to_string(i) : "M117 L" + std::to_string(i));
    return job;
}

}  // namespace

TEST_F(MarlinLinkTest, HandshakeResetsNumberingAndReadsCapabilities) {
    start({.emergency_parser = true});  // a build with EMERGENCY_PARSER, as the cell's should be
    EXPECT_EQ(link_.state(), DeviceState::active);
    const auto log = mock_->executed();
    ASSERT_GE(log.size(), 3u);
    EXPECT_EQ(log[0].text, "M110 N0");
    EXPECT_EQ(log[0].line, 0);
    EXPECT_EQ(log[1].text, "M115");
    EXPECT_EQ(log[2].text, "M155 S1");
    EXPECT_TRUE(link_.capabilities().at("EMERGENCY_PARSER"));
    EXPECT_TRUE(link_.emergency_parser());
}

TEST_F(MarlinLinkTest, ABoardWithoutTheEmergencyParserIsToldApart) {
    start();  // the mock's default: stock Marlin 1.1.9 as built for the GT2560
    EXPECT_EQ(link_.state(), DeviceState::active);
    EXPECT_FALSE(link_.capabilities().at("EMERGENCY_PARSER"));
    EXPECT_FALSE(link_.emergency_parser());
}

TEST_F(MarlinLinkTest, TheMockAnswersAsMarlin119OnTheGt2560) {
    start();
    const auto caps = link_.capabilities();
    EXPECT_TRUE(caps.at("AUTOREPORT_TEMP"));
    EXPECT_TRUE(caps.at("THERMAL_PROTECTION"));
    // Cold: the E part of the move is refused (Marlin's PREVENT_COLD_EXTRUSION), the line is
    // still acknowledged; M302 P1 allows it.
    ASSERT_TRUE(finish(link_.submit({"M83", "T1", "G1 E5 F600", "M400"}), 10s).ok());
    EXPECT_EQ(mock_->cold_extrusion_refusals(), 1u);
    ASSERT_TRUE(finish(link_.submit({"M302 P1", "G1 E5 F600", "M400"}), 10s).ok());
    EXPECT_EQ(mock_->cold_extrusion_refusals(), 1u);
}

TEST_F(MarlinLinkTest, TenThousandLinesWithOnePercentCorruptionRunExactlyOnceInOrder) {
    start();
    const auto job = numbered_job(10'000);
    std::mt19937 rng(42);
    std::uniform_int_distribution<std::int64_t> pick(10, 10'000);
    for (int i = 0; i < 100; ++i) mock_->corrupt_line(pick(rng));
    const CommandOutcome out = finish(link_.submit(job), 120s);
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;
    EXPECT_EQ(executed_job(), job);
    EXPECT_GE(link_.stats().resend_requests, 90u);
    EXPECT_EQ(mock_->rx_bytes_dropped(), 0u);
}

// Marlin 1.1.9's receive limits (BUFSIZE 4, a 128-byte RX ring that loses what overflows it):
// the widest window the cell config allows, lines near the 96-byte limit, and moves that hold
// the board's queue, so the host always has more to send than the board can take.
TEST_F(MarlinLinkTest, AFloodAtTheWidestWindowLosesNothingOnMarlinsLimits) {
    sim::MockGt2560Options mo;
    mo.min_extrude_temp_c = 0;
    MarlinLinkConfig lc;
    lc.protocol.window_lines = 3;   // the most extruder.link allows (BUFSIZE 4 - 1)
    lc.protocol.window_bytes = 120;  // likewise, under the 128-byte ring
    ASSERT_EQ(mo.rx_buffer_bytes, 128);
    ASSERT_EQ(mo.command_buffer_lines, 4);
    start(mo, lc);
    std::vector<std::string> job;
    for (int i = 0; i < 600; ++i)
        job.push_back(i % 3 == 0 ? "G1 E0.01 F600"
                                 : "M117 " + std::string(70, static_cast<char>('a' + i % 26)));
    const CommandOutcome out = finish(link_.submit(job), 120s);
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;
    EXPECT_EQ(executed_job(), job);
    EXPECT_EQ(mock_->rx_bytes_dropped(), 0u);
    EXPECT_EQ(link_.stats().resend_requests, 0u);
}

// The same mock does lose bytes past its ring: a host that writes without waiting for ok.
TEST_F(MarlinLinkTest, TheMocksRingLosesWhatOverflowsIt) {
    sim::MockGt2560Options mo;
    mo.link_path = (dir_ / "ttyGT2560").string();
    mo.bootloader_s = 0.01;
    mock_ = std::make_unique<sim::MockGt2560>(mo);
    const int fd = ::open(mock_->port_path().c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    std::string heard;  // the open reset the board: wait for its boot
    ASSERT_TRUE(eventually([&] {
        char buf[256];
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n > 0) heard.append(buf, static_cast<std::size_t>(n));
        return heard.find("start\n") != std::string::npos;
    }, 5s)) << heard;
    // Four dwells fill BUFSIZE and keep it full for seconds; the lines after them wait in the ring.
    std::string burst = "G4 P3000\nG4 P3000\nG4 P3000\nG4 P3000\n";
    for (int i = 0; i < 8; ++i) burst += "M117 " + std::string(40, 'x') + "\n";
    ASSERT_EQ(::write(fd, burst.data(), burst.size()), static_cast<ssize_t>(burst.size()));
    EXPECT_TRUE(eventually([&] { return mock_->rx_bytes_dropped() > 0; }, 5s));
    EXPECT_LE(mock_->rx_bytes_dropped(), burst.size() - 128);
    ::close(fd);
}

TEST_F(MarlinLinkTest, ResendWithoutOkIsDetectedAndHandled) {
    sim::MockGt2560Options mo;
    mo.resend_ok = false;
    MarlinLinkConfig lc;
    lc.protocol.resend_ok_wait = Seconds(0.05);
    start(mo, lc);
    const auto job = numbered_job(300);
    for (std::int64_t k : {20, 21, 150, 151, 290}) mock_->corrupt_line(k);
    mock_->duplicate_line(100);
    const CommandOutcome out = finish(link_.submit(job));
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;
    EXPECT_EQ(executed_job(), job);
}

TEST_F(MarlinLinkTest, LostOkIsRecoveredWithoutRunningAnythingTwice) {
    MarlinLinkConfig lc;
    lc.protocol.ok_timeout = Seconds(0.1);
    lc.protocol.probe_settle = Seconds(0.05);
    start({}, lc);
    const auto job = numbered_job(60);
    mock_->swallow_ok(20);   // executed, ok lost
    mock_->delay_ok(30, 0.3);  // ok late, after the timeout
    mock_->drop_line(40);    // line lost on the wire
    const CommandOutcome out = finish(link_.submit(job));
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;
    EXPECT_EQ(executed_job(), job);
    EXPECT_GE(link_.stats().timeouts, 3u);
}

// A lost M400 or G1 (no answer at all) is probed once the firmware's keepalive is overdue, not
// after the 300 s / 30 s of its class: the job goes on within seconds and nothing runs twice.
TEST_F(MarlinLinkTest, ALostBlockingLineIsProbedWhenItsKeepaliveIsOverdue) {
    MarlinLinkConfig lc;
    lc.protocol.keepalive_liveness = Seconds(0.5);
    start({.keepalive_s = 0.1}, lc);
    // A dwell long enough for a busy line: the firmware keeps blocking lines alive.
    ASSERT_TRUE(finish(link_.submit({"G4 P300"})).ok());
    job_start_ = mock_->executed_count();
    const std::int64_t first = *mock_->executed().back().line + 1;
    const std::vector<std::string> job = {"G1 E1 F300", "M400", "G1 E2 F300", "M400", "M117 done"};
    mock_->drop_line(first + 1);  // the first M400
    mock_->drop_line(first + 2);  // the G1 after it
    // Within finish()'s 30 s: M400's class alone would wait 300 s.
    const CommandOutcome out = finish(link_.submit(job));
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;
    EXPECT_EQ(executed_job(), job);
    EXPECT_GE(link_.stats().timeouts, 2u);
}

TEST_F(MarlinLinkTest, LongHeatingWaitDoesNotTimeOut) {
    sim::MockGt2560Options mo;
    mo.time_scale = 400;  // ~4 simulated minutes of heating in about 0.6 s
    MarlinLinkConfig lc;
    lc.protocol.ok_timeout = Seconds(0.1);   // far shorter than the wait
    lc.protocol.heating_liveness = Seconds(0.5);
    start(mo, lc);
    const auto t0 = std::chrono::steady_clock::now();
    const CommandOutcome out = finish(link_.submit({"M109 T0 S200", "M105"}));
    const double real_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;
    EXPECT_GE(mock_->temperature_c(0), 199.0);
    const auto log = mock_->executed();
    ASSERT_GE(log.size(), 2u);
    const double heat_s = log[log.size() - 2].t_s - log[job_start_ - 1].t_s;
    EXPECT_EQ(log[log.size() - 2].text, "M109 T0 S200");
    EXPECT_GT(heat_s, 120.0);  // simulated minutes
    EXPECT_GT(real_s, 0.1);    // longer than the normal ok timeout
    EXPECT_EQ(link_.stats().timeouts, 0u);
}

TEST_F(MarlinLinkTest, AbortBreaksAHeatingWaitPromptly) {
    sim::MockGt2560Options mo;
    mo.time_scale = 50;  // the full wait would take several real seconds
    mo.emergency_parser = true;
    start(mo);
    auto job = link_.submit({"M109 T1 S250", "G1 E5 F300", "M117 after"});
    ASSERT_TRUE(eventually([&] { return mock_->temperature_c(1) > 40.0; }));
    link_.abort();
    const CommandOutcome out = finish(std::move(job), 2s);
    EXPECT_EQ(out.failure, LinkFailure::aborted);
    ASSERT_TRUE(eventually([&] {
        const auto j = executed_job();
        return !j.empty() && j.back() == "M108";
    }));
    const auto j = executed_job();
    ASSERT_EQ(j.size(), 2u);  // the wait ended, then M108 passed the queue; nothing else ran
    EXPECT_EQ(j[0], "M109 T1 S250");
    EXPECT_LT(mock_->temperature_c(1), 200.0);
    EXPECT_TRUE(finish(link_.submit({"M105"}), 5s).ok());  // accounting intact
}

// Stock 1.1.9 has no emergency parser: M108 is read only once the M109 it should break has
// finished heating (why the link warns about such a board). The wait's end is its log entry.
TEST_F(MarlinLinkTest, WithoutTheEmergencyParserAnAbortWaitsForTheHeatingToEnd) {
    sim::MockGt2560Options mo;
    mo.time_scale = 50;
    start(mo);
    auto job = link_.submit({"M109 T1 S250", "G1 E5 F300", "M117 after"});
    ASSERT_TRUE(eventually([&] { return mock_->temperature_c(1) > 40.0; }));
    link_.abort();
    EXPECT_EQ(finish(std::move(job), 2s).failure, LinkFailure::aborted);  // the host stops waiting
    ASSERT_TRUE(eventually([&] { return !executed_job().empty(); }, 30s));
    EXPECT_GE(mock_->temperature_c(1), 249.0);  // the wait ran to its end
    EXPECT_EQ(executed_job(), std::vector<std::string>{"M109 T1 S250"});  // and nothing after it
}

TEST_F(MarlinLinkTest, CutAfterM400FiresOnlyWhenTheFeedHasFinished) {
    sim::MockGt2560Options mo;
    mo.time_scale = 20;
    start(mo);
    const CommandOutcome out = finish(link_.submit(
        {"T1", "M83", "G1 E20 F300", "M400", "M42 P11 S255", "G4 P50", "M42 P11 S0"}));
    ASSERT_TRUE(out.ok()) << out.detail;
    const auto pins = mock_->pin_events();
    ASSERT_EQ(pins.size(), 2u);
    EXPECT_EQ(pins[0].command, "M42 P11 S255");
    EXPECT_EQ(pins[0].planner_blocks_pending, 0);
    EXPECT_GE(pins[0].t_s, pins[0].last_move_end_s);
    EXPECT_GE(pins[1].t_s, pins[0].t_s + 0.05);
}

TEST_F(MarlinLinkTest, CutWithoutM400FiresWhileTheFeedIsStillRunning) {
    sim::MockGt2560Options mo;
    mo.time_scale = 20;
    start(mo);
    // M302 P1: extrude cold (these tests are about timing, not heat), as a host would on a bench.
    ASSERT_TRUE(finish(link_.submit({"M302 P1", "T1", "M83", "G1 E20 F300", "M42 P11 S255"})).ok());
    const auto pins = mock_->pin_events();
    ASSERT_EQ(pins.size(), 1u);
    EXPECT_EQ(pins[0].planner_blocks_pending, 1);  // why the controller always syncs first
    EXPECT_LT(pins[0].t_s, pins[0].last_move_end_s);
}

// The ok of a G1 comes when the planner takes it; the move runs later, after the ones before it.
TEST_F(MarlinLinkTest, MovesRunBackToBackAfterTheirOks) {
    sim::MockGt2560Options mo;
    mo.time_scale = 20;
    start(mo);
    ASSERT_TRUE(finish(link_.submit({"M302 P1", "T1", "M83", "G1 E20 F300", "G1 E-1 F2400"})).ok());
    const auto log = mock_->executed();
    ASSERT_GE(log.size(), 2u);
    const auto& feed = log[log.size() - 2];
    const auto& retract = log.back();
    ASSERT_EQ(feed.text, "G1 E20 F300");
    ASSERT_TRUE(feed.move_start_s && feed.move_end_s && retract.move_start_s && retract.move_end_s);
    EXPECT_NEAR(*feed.move_end_s - *feed.move_start_s, 20.0 / 5.0, 1e-9);     // 20 mm at 5 mm/s
    EXPECT_NEAR(*retract.move_start_s, *feed.move_end_s, 1e-9);               // queued behind it
    EXPECT_NEAR(*retract.move_end_s - *retract.move_start_s, 1.0 / 40.0, 1e-9);
    EXPECT_LT(retract.t_s, *retract.move_start_s);  // its ok long before it runs
    EXPECT_FALSE(log[log.size() - 3].move_start_s);  // M83 is no move
}

TEST_F(MarlinLinkTest, ABoundedLogKeepsTheNewestAndCountsThemAll) {
    sim::MockGt2560Options mo;
    mo.max_log = 5;
    start(mo);
    const std::size_t before = mock_->executed_count();  // the handshake's
    ASSERT_GE(before, 3u);
    ASSERT_TRUE(finish(link_.submit(numbered_job(12))).ok());
    const std::vector<std::string> job = numbered_job(12);
    EXPECT_EQ(mock_->executed_count(), before + 12);
    // The last five, numbered in the order they ran.
    const auto log = mock_->executed();
    ASSERT_EQ(log.size(), 5u);
    for (std::size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(log[i].text, job[7 + i]);
        EXPECT_EQ(log[i].number, before + 7 + i);
    }
    // From a number still kept; from one dropped: what is kept; past the end: nothing.
    const auto since = mock_->executed_since(before + 10);
    ASSERT_EQ(since.size(), 2u);
    EXPECT_EQ(since[0].text, job[10]);
    EXPECT_EQ(mock_->executed_since(0).size(), 5u);
    EXPECT_TRUE(mock_->executed_since(before + 12).empty());
    EXPECT_TRUE(mock_->wait_for_executed(before + 12, 0ms));
}

TEST_F(MarlinLinkTest, ResetMidJobFailsTheJobAndNeverRenumbers) {
    start();
    mock_->reset_at_line(50);
    const CommandOutcome out = finish(link_.submit(numbered_job(200)));
    EXPECT_EQ(out.failure, LinkFailure::firmware_reset);
    EXPECT_EQ(link_.state(), DeviceState::error);
    EXPECT_EQ(link_.fault(), LinkFailure::firmware_reset);
    const auto done = executed_job();
    EXPECT_LT(done.size(), 50u);
    reconnect();
    EXPECT_TRUE(finish(link_.submit({"M105"})).ok());
}

TEST_F(MarlinLinkTest, CablePullIsALinkErrorAndReconnectIsClean) {
    sim::MockGt2560Options mo;
    start(mo);
    auto job = link_.submit({"G4 S5", "M117 never"});
    ASSERT_TRUE(eventually([&] { return link_.stats().lines_sent >= 4; }));  // G4 on the wire
    mock_->unplug();
    const CommandOutcome out = finish(std::move(job), 5s);
    EXPECT_EQ(out.failure, LinkFailure::link_lost) << out.detail;
    EXPECT_EQ(link_.state(), DeviceState::error);
    mock_->replug();
    reconnect();
    const auto job2 = numbered_job(20);
    ASSERT_TRUE(finish(link_.submit(job2)).ok());
    EXPECT_EQ(executed_job(), job2);
}

TEST_F(MarlinLinkTest, GarbledResendNumberIsALinkError) {
    start();
    mock_->corrupt_line(30);
    mock_->garble_next_resend();
    const CommandOutcome out = finish(link_.submit(numbered_job(100)));
    EXPECT_EQ(out.failure, LinkFailure::resend_out_of_window) << out.detail;
    EXPECT_EQ(link_.state(), DeviceState::error);
}

TEST_F(MarlinLinkTest, EmergencyStopKillsTheFirmware) {
    sim::MockGt2560Options mo;
    mo.time_scale = 10;
    mo.emergency_parser = true;  // at once, inside the heating wait
    start(mo);
    auto job = link_.submit({"M109 T0 S200", "M117 never"});
    ASSERT_TRUE(eventually([&] { return mock_->temperature_c(0) > 25.0; }));
    link_.emergency_stop();
    EXPECT_EQ(finish(std::move(job), 5s).failure, LinkFailure::emergency_stop);
    EXPECT_TRUE(eventually([&] { return mock_->killed(); }));
    EXPECT_EQ(link_.state(), DeviceState::error);
}

TEST_F(MarlinLinkTest, ThermalRunawayHaltsTheJob) {
    sim::MockGt2560Options mo;
    mo.time_scale = 10;
    start(mo);
    auto job = link_.submit({"M109 T0 S200", "M117 never"});
    mock_->thermal_runaway(0);
    EXPECT_EQ(finish(std::move(job), 5s).failure, LinkFailure::firmware_halted);
}

TEST_F(MarlinLinkTest, SilentFirmwareTimesOut) {
    MarlinLinkConfig lc;
    lc.protocol.ok_timeout = Seconds(0.05);
    lc.protocol.max_probes = 2;
    start({}, lc);
    mock_->go_silent(true);
    const CommandOutcome out = finish(link_.submit({"M117 hello"}), 5s);
    EXPECT_EQ(out.failure, LinkFailure::ack_timeout) << out.detail;
}

TEST_F(MarlinLinkTest, BadLinesAreRejectedBeforeAnythingIsSent) {
    start();
    try {
        link_.submit({"G1 E1", "M117 " + std::string(100, 'x')});
        FAIL() << "expected LineError";
    } catch (const LineError& e) {
        EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    }
    EXPECT_THROW(link_.submit({"M112"}), LineError);
    EXPECT_TRUE(executed_job().empty());
}

// Filament per extruder as the board took it, through resends, lost oks and a reconnect: the
// link's ledger against a sum of the E words the mock executed, counted here on their own.
TEST_F(MarlinLinkTest, TheFeedLedgerChargesWhatTheBoardRanToEachExtruder) {
    MarlinLinkConfig lc;
    lc.protocol.ok_timeout = Seconds(0.1);
    lc.protocol.motion_timeout = Seconds(0.3);  // the lost ok of a move: probed soon
    lc.protocol.probe_settle = Seconds(0.05);
    start({.time_scale = 50, .min_extrude_temp_c = 0}, lc);
    std::vector<std::string> job{"M83"};
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> e(-1.0, 4.0);
    for (int i = 0; i < 300; ++i) {
        if (i % 25 == 0) job.push_back(i % 50 == 0 ? "T1" : "T0");
        char l[48];
        std::snprintf(l, sizeof l, "G1 E%.5f F3000", e(rng));
        job.push_back(l);
    }
    for (std::int64_t k : {40, 90, 150, 220}) mock_->corrupt_line(k);
    mock_->swallow_ok(60);
    mock_->delay_ok(120, 0.3);
    mock_->drop_line(180);
    const CommandOutcome out = finish(link_.submit(job), 60s);
    ASSERT_TRUE(out.ok()) << to_string(out.failure) << " " << out.detail;

    const auto ran = [&] {
        std::array<double, 2> by_tool{};
        int tool = 0;
        for (const auto& c : mock_->executed()) {
            if (c.text == "T0" || c.text == "T1") tool = c.text[1] - '0';
            if (c.text.rfind("G1 E", 0) == 0) by_tool[static_cast<std::size_t>(tool)] += std::stod(c.text.substr(4));
        }
        return by_tool;
    };
    const auto board = ran();
    EXPECT_NEAR(link_.fed().of(0), board[0], 1e-9);
    EXPECT_NEAR(link_.fed().of(1), board[1], 1e-9);
    EXPECT_GT(board[1], 100.0);

    // A reconnect reboots the board (absolute E on T0); the totals carry on.
    link_.deactivate();
    link_.activate();
    ASSERT_TRUE(finish(link_.submit({"T1", "G1 E2.5 F3000", "G1 E3 F3000"})).ok());
    EXPECT_NEAR(link_.fed().of(1), board[1] + 3.0, 1e-9);
}

// Marlin drops the E of a move on a cold hotend and still answers ok: nothing was fed.
TEST_F(MarlinLinkTest, AColdExtrusionRefusalIsNotCharged) {
    start({.time_scale = 50});  // hotends at room temperature, PREVENT_COLD_EXTRUSION at 170
    ASSERT_TRUE(finish(link_.submit({"M83", "T1", "G1 E5 F3000", "G1 E5 F3000"})).ok());
    EXPECT_EQ(mock_->cold_extrusion_refusals(), 2u);
    EXPECT_EQ(link_.fed().of(1), 0.0);
    ASSERT_TRUE(finish(link_.submit({"M302 P1", "G1 E5 F3000"})).ok());  // cold extrusion allowed
    EXPECT_NEAR(link_.fed().of(1), 5.0, 1e-9);
}

// An abort drops the lines not sent yet, and the next lines take their numbers: their oks must
// not charge the dropped moves (they were, once: a stopped print's fibre 13 mm over the board's).
TEST_F(MarlinLinkTest, MovesAnAbortDroppedAreNotChargedWhenTheirNumbersComeAgain) {
    start({.emergency_parser = true, .min_extrude_temp_c = 0});
    ASSERT_TRUE(finish(link_.submit({"M83", "T1", "G1 E2 F3000"})).ok());
    const auto sent = link_.stats().lines_sent;
    auto held = link_.submit({"G4 S1", "G1 E5 F3000", "G1 E7 F3000"});  // the dwell holds the rest
    ASSERT_TRUE(eventually([&] { return link_.stats().lines_sent > sent; }));  // G4 on the wire
    link_.abort();
    EXPECT_EQ(finish(std::move(held)).failure, LinkFailure::aborted);
    ASSERT_TRUE(finish(link_.submit({"M117 a", "M117 b", "M117 c"})).ok());
    for (const std::string& c : executed_job()) EXPECT_NE(c, "G1 E5 F3000");
    EXPECT_NEAR(link_.fed().of(1), 2.0, 1e-9);
}
