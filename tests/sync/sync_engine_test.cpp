// The sync engine in a real small cell (sync_test_cell.hpp): the board's executed log command by
// command for a whole two-layer print, the hotend wait at a head switch, a gap caught up in
// order, a duplicate ignored, the 16-bit counter wrap, pause and resume inside a fibre path, a
// barrier held by a pause, and corrupted serial lines.
#include "sync_test_cell.hpp"

#include <gmock/gmock.h>

#include <algorithm>
#include <map>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::ElementsAre;

namespace {

// The program's events as the tests use them (checked in ProgramIsTheOneTheTestsAssume).
constexpr int head_switch_pla = 1, extrude_on = 2, extrude_off = 3, layer0_end = 4,
              head_switch_ccf = 5, fibre_start = 6, cut = 7, path_end = 8, layer1_end = 9;

std::vector<std::int64_t> sequences(const std::vector<EventDone>& done) {
    std::vector<std::int64_t> out;
    for (const auto& d : done) out.push_back(d.sequence);
    return out;
}

}  // namespace

class SyncEngineTest : public SyncCellTest {
  protected:
    const drivers::abb::ProgramEvent& ev(int n) const {
        return program_.events.at(static_cast<std::size_t>(n - 1));
    }
    // Plays events first..last, adding each event's expected commands to `expect` and waiting
    // until the board has run them (at a metered path: all of its feed, as the robot takes that
    // long to reach the path's end).
    void play(Expected& expect, int first, int last) {
        for (int n = first; n <= last; ++n) {
            const auto& e = ev(n);
            const Head head = e.nozzle == drivers::abb::Nozzle::pla ? Head::pla : Head::ccf;
            switch (e.kind) {
                case EventKind::head_switch: expect.head_switch(head); break;
                case EventKind::extrude_on: expect.extrude_on(e.length_mm, e.speed_mm_s); break;
                case EventKind::extrude_off: expect.extrude_off(); break;
                case EventKind::fibre_start: expect.fibre_start(e.length_mm, e.speed_mm_s); break;
                case EventKind::cut: expect.cut(); break;
                case EventKind::path_end:
                case EventKind::layer_end: break;
            }
            robot_at(n);
            board_ran(expect.lines.size());
        }
    }
};

TEST_F(SyncEngineTest, ProgramIsTheOneTheTestsAssume) {
    ASSERT_EQ(program_.events.size(), 9u);
    EXPECT_EQ(ev(head_switch_pla).kind, EventKind::head_switch);
    EXPECT_EQ(ev(extrude_on).kind, EventKind::extrude_on);
    EXPECT_EQ(ev(extrude_off).kind, EventKind::extrude_off);
    EXPECT_EQ(ev(layer0_end).kind, EventKind::layer_end);
    EXPECT_EQ(ev(head_switch_ccf).kind, EventKind::head_switch);
    EXPECT_EQ(ev(fibre_start).kind, EventKind::fibre_start);
    EXPECT_EQ(ev(cut).kind, EventKind::cut);
    EXPECT_EQ(ev(path_end).kind, EventKind::path_end);
    EXPECT_EQ(ev(layer1_end).kind, EventKind::layer_end);
    EXPECT_DOUBLE_EQ(ev(extrude_on).length_mm, 80);
    EXPECT_DOUBLE_EQ(ev(extrude_on).speed_mm_s, 12);
    EXPECT_NEAR(ev(fibre_start).length_mm, 58, 1e-9);
    EXPECT_DOUBLE_EQ(ev(fibre_start).speed_mm_s, 5);
    EXPECT_TRUE(ev(head_switch_ccf).barrier);
    EXPECT_TRUE(ev(fibre_start).barrier);
}

TEST_F(SyncEngineTest, AWholePrintGivesExactlyTheIntendedBoardCommands) {
    boot();
    start_engine();
    Expected expect;
    expect.start();
    play(expect, head_switch_pla, layer1_end);
    confirmed(layer1_end);

    EXPECT_EQ(executed_job(), expect.lines);
    // Physically: the fibre fed along the path between the threading M400 and the cut adds up to
    // the fibre length, the PLA to the line's volume over the filament's cross-section.
    const auto log = executed_job();
    const auto thread_end = static_cast<std::size_t>(std::find(log.begin(), log.end(), "M400") - log.begin());
    const auto cut_start = static_cast<std::size_t>(std::find(log.begin() + static_cast<std::ptrdiff_t>(thread_end) + 1, log.end(), "M400") - log.begin());
    EXPECT_NEAR(sum_e(log, thread_end + 1, cut_start), 58.0, 1e-6);

    const SyncStatus s = engine_->status();
    EXPECT_TRUE(s.finished);
    EXPECT_FALSE(s.faulted) << s.fault_reason;
    EXPECT_EQ(s.pending, 0);
    EXPECT_EQ(s.stats.pieces_sent, 40u + 58u);
    EXPECT_EQ(s.stats.feed_left_at_cut, 0u);
    EXPECT_EQ(s.stats.extrusion_left_at_off, 0u);
    EXPECT_EQ(s.stats.paths_completed, 1u);
    EXPECT_EQ(s.stats.heat_waits, 0u);  // preheated
    EXPECT_EQ(s.stats.gaps, 0u);
    EXPECT_EQ(s.stats.duplicates, 1u);  // the link's first report: the run request's 0
    EXPECT_THAT(sequences(done()), ElementsAre(1, 2, 3, 4, 5, 6, 7, 8, 9));
    ASSERT_EQ(done().size(), 9u);
    EXPECT_TRUE(done()[fibre_start - 1].released);
    EXPECT_THAT(progress_layers(), ElementsAre(0, 1));
    EXPECT_EQ(server_->commands().release, fibre_start);
    EXPECT_FALSE(server_->commands().pause);
    // Self-measurement: one sample per event with board commands (two head switches).
    std::map<EventKind, std::size_t> counts;
    for (const auto& k : s.stats.timing) {
        counts[k.kind] = k.submit_ms.count;
        EXPECT_EQ(k.ok_ms.count, k.submit_ms.count) << to_string(k.kind);
        EXPECT_GE(k.ok_ms.median, k.submit_ms.median) << to_string(k.kind);
        EXPECT_LE(k.submit_ms.median, k.submit_ms.max);
    }
    EXPECT_EQ(counts, (std::map<EventKind, std::size_t>{{EventKind::extrude_on, 1},
                                                         {EventKind::extrude_off, 1},
                                                         {EventKind::fibre_start, 1},
                                                         {EventKind::cut, 1},
                                                         {EventKind::head_switch, 2}}));
}

TEST_F(SyncEngineTest, ColdHotendIsHeatedBeforeTheHeadSwitchIsReleased) {
    boot(false);
    start_engine({}, false);
    robot_at(head_switch_pla);
    // Released only after the ok of the wait, so the hotend is in its window by now.
    EXPECT_GE(mock_->temperature_c(0), 199.0);
    Expected expect;
    expect.start();
    expect.head_switch(Head::pla);
    expect.lines.push_back("M109 T0 S200");
    board_ran(expect.lines.size());
    EXPECT_EQ(executed_job(), expect.lines);
    EXPECT_EQ(engine_->status().stats.heat_waits, 1u);
}

TEST_F(SyncEngineTest, AGapIsCaughtUpInOrder) {
    boot();
    start_engine();
    Expected expect;
    expect.start();
    play(expect, head_switch_pla, extrude_on);
    // The robot passes 3 and 4 between two polls and stops at barrier 5.
    expect.extrude_off();
    expect.head_switch(Head::ccf);
    robot_at(head_switch_ccf);
    board_ran(expect.lines.size());
    confirmed(head_switch_ccf);
    EXPECT_EQ(executed_job(), expect.lines);
    EXPECT_THAT(sequences(done()), ElementsAre(1, 2, 3, 4, 5));
    const SyncStatus s = engine_->status();
    EXPECT_EQ(s.stats.gaps, 1u);
    EXPECT_EQ(s.stats.events_caught_up, 2u);
    EXPECT_THAT(progress_layers(), ElementsAre(0));
}

TEST_F(SyncEngineTest, ADuplicateCounterValueIsIgnored) {
    boot();
    start_engine();
    Expected expect;
    expect.start();
    play(expect, head_switch_pla, extrude_on);
    confirmed(extrude_on);
    // As the link would report it again after a reconnect.
    drivers::abb::EventCounterChange again;
    again.value = extrude_on;
    again.first_read = again.accepted = std::chrono::steady_clock::now();
    engine_->robot_event(again);
    ASSERT_TRUE(eventually([&] { return engine_->status().stats.duplicates == 2; }));
    EXPECT_EQ(engine_->status().last_received, extrude_on);
    // Anything it wrongly sent for the duplicate would stand in the board's log before the next
    // event's commands.
    play(expect, extrude_off, extrude_off);
    confirmed(extrude_off);
    EXPECT_EQ(executed_job(), expect.lines);
}

TEST_F(SyncEngineTest, TheCounterWrapsPast65535) {
    // 65538 events without board commands; the run resumes after event 65533.
    program_.events.clear();
    for (int n = 1; n <= 65538; ++n)
        program_.events.push_back({.sequence = n, .kind = EventKind::layer_end, .layer = n});
    boot();
    start_engine({.first_event = 65534});
    for (std::int64_t n : {65534, 65535, 65536, 65538}) {
        server_->set_event_number(static_cast<std::uint16_t>(n % 65536));  // 0, then 2: a gap
        confirmed(n);
    }
    EXPECT_THAT(sequences(done()), ElementsAre(65534, 65535, 65536, 65537, 65538));
    const SyncStatus s = engine_->status();
    EXPECT_FALSE(s.faulted) << s.fault_reason;
    EXPECT_TRUE(s.finished);
    EXPECT_EQ(s.stats.counter_resets, 1u);  // the link's first report, 0, on a resumed run
}

TEST_F(SyncEngineTest, PauseInsideAFibrePathLosesAndRepeatsNoFeed) {
    boot();
    start_engine();
    Expected expect;
    expect.start();
    play(expect, head_switch_pla, head_switch_ccf);
    expect.fibre_start(ev(fibre_start).length_mm, ev(fibre_start).speed_mm_s);
    const std::size_t threaded = expect.lines.size() - 58;
    robot_at(fibre_start);
    board_ran(threaded + 10);  // about 2 simulated s into the path

    engine_->pause();
    ASSERT_TRUE(eventually([&] { return engine_->status().paused; }));
    EXPECT_TRUE(server_->wait_for_commands([](const auto& c) { return c.pause; }, 5s));
    const std::size_t sent = engine_->status().metering.pieces_sent;
    EXPECT_LT(sent, 58u);
    // 3 simulated s on the board's clock: 15 pieces at the path's pace if it went on.
    const double paused_at_s = mock_->sim_now_s();
    ASSERT_TRUE(eventually([&] { return mock_->sim_now_s() >= paused_at_s + 3.0; }));
    EXPECT_EQ(engine_->status().metering.pieces_sent, sent);
    EXPECT_LE(executed_job().size(), threaded + sent);

    engine_->resume();
    EXPECT_TRUE(server_->wait_for_commands([](const auto& c) { return !c.pause; }, 5s));
    board_ran(expect.lines.size());
    play(expect, cut, layer1_end);
    confirmed(layer1_end);

    const auto log = executed_job();
    EXPECT_EQ(log, expect.lines);  // every piece once, in order
    EXPECT_NEAR(sum_e(log, threaded, threaded + 58), 58.0, 1e-6);
    const SyncStatus s = engine_->status();
    EXPECT_EQ(s.stats.feed_left_at_cut, 0u);
    EXPECT_FALSE(s.paused);
}

TEST_F(SyncEngineTest, ARobotThatOutrunsTheFeedLeavesShortfallsOnItsPath) {
    boot();
    SyncOptions o;
    o.late_cut_mm = 1e-6;  // any cut the robot did not stand for is late here
    start_engine(o);
    Expected expect;
    expect.start();
    play(expect, head_switch_pla, head_switch_ccf);
    ASSERT_FALSE(ev(cut).barrier);  // the robot runs on through the cut
    // The robot reaches the cut right after the fibre's start: the feed cannot have kept up.
    robot_at(fibre_start);
    robot_at(cut);
    confirmed(cut);
    const SyncStatus s = engine_->status();
    ASSERT_EQ(s.stats.feed_left_at_cut, 1u);
    EXPECT_GT(s.stats.feed_left_at_cut_mm, 10.0);
    EXPECT_EQ(s.stats.late_cuts, 1u);
    ASSERT_EQ(s.stats.shortfalls.size(), 2u);
    const auto& dropped = s.stats.shortfalls[0];
    EXPECT_EQ(dropped.kind, daemon::sync::ShortfallKind::fibre_feed_dropped);
    EXPECT_EQ(dropped.sequence, fibre_start);
    EXPECT_EQ(dropped.layer, ev(fibre_start).layer);
    EXPECT_EQ(dropped.path, ev(fibre_start).path);
    EXPECT_DOUBLE_EQ(dropped.mm, s.stats.feed_left_at_cut_mm);
    // What the board fed plus what was dropped is the path.
    const auto log = executed_job();
    const auto thread_end =
        static_cast<std::size_t>(std::find(log.begin(), log.end(), "M400") - log.begin());
    const auto cut_start = static_cast<std::size_t>(
        std::find(log.begin() + static_cast<std::ptrdiff_t>(thread_end) + 1, log.end(), "M400") -
        log.begin());
    EXPECT_NEAR(sum_e(log, thread_end + 1, cut_start) + dropped.mm, 58.0, 1e-6);
    const auto& late = s.stats.shortfalls[1];
    EXPECT_EQ(late.kind, daemon::sync::ShortfallKind::late_cut);
    EXPECT_EQ(late.sequence, cut);
    EXPECT_GT(late.mm, 0.0);
}

TEST_F(SyncEngineTest, ABarrierReachedWhilePausedIsReleasedOnResume) {
    boot();
    start_engine();
    engine_->pause();
    ASSERT_TRUE(eventually([&] { return engine_->status().paused; }));
    server_->set_barrier_number(head_switch_pla);
    server_->set_event_number(head_switch_pla);
    ASSERT_TRUE(eventually([&] { return engine_->status().held_barrier == head_switch_pla; }));
    Expected expect;
    expect.start();
    expect.head_switch(Head::pla);
    board_ran(expect.lines.size());  // the board's part is done ...
    ASSERT_TRUE(eventually([&] { return done().size() == 1; }));  // ... and the event confirmed:
    EXPECT_FALSE(done()[0].released);
    // a release would have been written by the link's next polls.
    const auto polls = robot_->snapshot().stats.polls;
    ASSERT_TRUE(eventually([&] { return robot_->snapshot().stats.polls >= polls + 3; }));
    EXPECT_EQ(server_->commands().release, 0);  // ... but the robot stays held
    EXPECT_TRUE(server_->commands().pause);
    ASSERT_EQ(done().size(), 1u);

    engine_->resume();
    EXPECT_TRUE(server_->wait_for_commands(
        [](const auto& c) { return c.release == head_switch_pla && !c.pause; }, 5s));
    EXPECT_FALSE(engine_->status().held_barrier.has_value());
}

TEST_F(SyncEngineTest, CorruptedSerialLinesLeaveTheBoardLogIdentical) {
    boot();
    // The job's first line number: the one after the last line the board has executed.
    const std::int64_t first = *mock_->executed().back().line + 1;
    for (std::int64_t k : {first + 1, first + 12, first + 30, first + 70, first + 100})
        mock_->corrupt_line(k);
    start_engine();
    Expected expect;
    expect.start();
    play(expect, head_switch_pla, layer1_end);
    confirmed(layer1_end);
    EXPECT_EQ(executed_job(), expect.lines);
    EXPECT_GE(board_.stats().resend_requests, 5u);
    EXPECT_FALSE(engine_->status().faulted);
}
