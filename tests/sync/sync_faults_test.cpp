// Sync faults in a real small cell (sync_test_cell.hpp): the robot's counter going back, the
// board unplugged in the middle of a fibre path, the robot I/O connection lost. Each ends in one
// fault with a reason, the robot asked to pause, and the last confirmed event kept for a resume.
#include "sync_test_cell.hpp"

#include <gmock/gmock.h>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

class SyncFaultTest : public SyncCellTest {
  protected:
    void expect_one_fault_containing(const std::string& text) {
        ASSERT_TRUE(eventually([&] { return engine_->status().faulted; }));
        const SyncStatus s = engine_->status();
        EXPECT_THAT(s.fault_reason, HasSubstr(text));
        EXPECT_TRUE(server_->wait_for_commands([](const auto& c) { return c.pause; }, 5s));
        engine_handled_all_posted();  // the fault's aftermath: board replies, link states
        EXPECT_THAT(faults(), ElementsAre(s.fault_reason));
    }
};

TEST_F(SyncFaultTest, TheCounterGoingBackIsAFault) {
    boot();
    start_engine();
    robot_at(1);
    server_->set_event_number(2);
    server_->set_event_number(3);  // extrude_off: the PLA feed stops
    ASSERT_TRUE(eventually([&] { return engine_->status().last_confirmed == 3; }));
    server_->set_event_number(2);
    expect_one_fault_containing("robot event counter went back from event 3 to 2");
    const auto board_lines = executed_job().size();
    server_->set_event_number(4);  // ignored after a fault
    // The link handed the change to the engine before it showed it; the engine took it in.
    ASSERT_TRUE(eventually([&] { return robot_->snapshot().event_counter == 4; }));
    engine_handled_all_posted();
    const SyncStatus s = engine_->status();
    EXPECT_EQ(s.last_confirmed, 3);
    EXPECT_EQ(s.last_received, 3);
    // M108 (the abort) is the only thing the board may still have run.
    const auto log = executed_job();
    ASSERT_GE(log.size(), board_lines);
    for (std::size_t i = board_lines; i < log.size(); ++i) EXPECT_EQ(log[i], "M108");
}

TEST_F(SyncFaultTest, TheBoardUnpluggedMidPathIsAFault) {
    boot();
    start_engine();
    for (int n = 1; n <= 5; ++n) {
        robot_at(n);
        if (n == 2) {  // let the PLA metering finish
            ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_sent == 40; }));
        }
    }
    robot_at(6);
    ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_sent >= 5; }));
    mock_->unplug();
    expect_one_fault_containing("extruder board: link_lost: serial");
    const SyncStatus s = engine_->status();
    EXPECT_EQ(s.last_confirmed, 6);
    EXPECT_FALSE(s.metering.active);
}

TEST_F(SyncFaultTest, TheRobotIoConnectionLostIsAFault) {
    boot();
    start_engine();
    robot_at(1);
    server_->refuse_connections_for(1s);
    server_->drop_connections();
    expect_one_fault_containing("robot I/O: modbus 127.0.0.1:");
    EXPECT_EQ(engine_->status().last_confirmed, 1);
}

TEST_F(SyncFaultTest, ANewEngineResumesAnInterruptedFibreFeedWithNothingLostOrRepeated) {
    constexpr int fibre_start = 6, cut = 7, layer1_end = 9;
    boot();
    start_engine();
    for (int n = 1; n < fibre_start; ++n) {
        robot_at(n);
        if (n == 2) {  // let the PLA metering finish
            ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_sent == 40; }));
        }
    }
    robot_at(fibre_start);
    ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_sent >= 15; }));
    server_->refuse_connections_for(300ms);
    server_->drop_connections();
    expect_one_fault_containing("robot I/O: modbus 127.0.0.1:");
    ASSERT_TRUE(eventually([&] { return engine_->status().metering.pieces_unanswered == 0; }));
    const SyncStatus faulted = engine_->status();
    EXPECT_EQ(faulted.last_confirmed, fibre_start);
    EXPECT_EQ(faulted.metering.sequence, fibre_start);
    EXPECT_FALSE(faulted.metering.active);
    const double fed = faulted.metering.e_fed_mm;
    EXPECT_GT(fed, 0);
    EXPECT_LT(fed, 58);
    // What the engine counts as fed is what the board ran after the threading M400.
    const auto before = executed_job();
    const auto threaded = std::find(before.begin(), before.end(), "M400");
    ASSERT_NE(threaded, before.end());
    const auto from = static_cast<std::size_t>(threaded - before.begin()) + 1;
    EXPECT_NEAR(sum_e(before, from, before.size()), fed, 1e-6);

    ASSERT_TRUE(robot_->wait_until_up(5s));
    board_.on_temperature(nullptr);
    SyncOptions o;
    o.time_scale = time_scale;
    o.first_event = faulted.last_confirmed + 1;
    o.resume_feed = daemon::sync::ResumeFeed{faulted.metering.sequence, fed};
    auto resumed = std::make_unique<SyncEngine>(program_, extruder_, board_, *robot_, o);
    resumed->start();
    engine_ = std::move(resumed);
    ASSERT_TRUE(eventually([&] {
        const SyncStatus s = engine_->status();
        return s.metering.active && s.metering.sequence == fibre_start &&
               s.metering.pieces_sent == s.metering.pieces_total && s.metering.pieces_unanswered == 0;
    }));
    for (int n = cut; n <= layer1_end; ++n) robot_at(n);
    confirmed(layer1_end);

    // The fibre's G1 E pieces between the threading M400 and the cut's: each of the path's
    // pieces exactly once, in order, across both engines.
    const auto log = executed_job();
    const auto thread_end = std::find(log.begin(), log.end(), "M400");
    const auto cut_start = std::find(thread_end + 1, log.end(), "M400");
    std::vector<std::string> fibre_pieces;
    for (auto it = thread_end + 1; it != cut_start; ++it)
        if (it->rfind("G1 E", 0) == 0) fibre_pieces.push_back(*it);
    EXPECT_EQ(fibre_pieces, metered_pieces(58, 1.0, 5, 1));
    const SyncStatus s = engine_->status();
    EXPECT_TRUE(s.finished);
    EXPECT_EQ(s.stats.feed_left_at_cut, 0u);
}

// A re-entry after a restart in the middle of a fibre path: the run starts at the path's
// fibre_start, threads the fibre anew, and meters only the feed after what the board took before.
TEST_F(SyncFaultTest, ARethreadedFibrePathFeedsOnlyWhatWasNotFedBefore) {
    constexpr int fibre_start = 6, cut = 7, layer1_end = 9;
    boot();
    SyncOptions o;
    o.first_event = fibre_start;
    const std::vector<std::string> all = metered_pieces(58, 1.0, 5, 1);
    constexpr std::size_t done_before = 20;
    double fed = 0;
    for (std::size_t i = 0; i < done_before; ++i) fed += std::stod(all[i].substr(4));
    o.resume_feed = daemon::sync::ResumeFeed{fibre_start, fed, true};
    start_engine(o);
    robot_at(fibre_start);  // the barrier: threaded (G1 E42, M400), then released
    ASSERT_TRUE(eventually([&] {
        const SyncStatus s = engine_->status();
        return s.metering.active && s.metering.pieces_sent == s.metering.pieces_total &&
               s.metering.pieces_unanswered == 0;
    }));
    EXPECT_NEAR(engine_->status().metering.e_fed_mm, 58, 1e-6);  // before and now
    for (int n = cut; n <= layer1_end; ++n) robot_at(n);
    confirmed(layer1_end);
    const auto log = executed_job();
    const auto thread_end = std::find(log.begin(), log.end(), "M400");
    ASSERT_NE(thread_end, log.end());
    EXPECT_EQ(std::count_if(log.begin(), thread_end,
                            [](const std::string& l) { return l.rfind("G1 E42.00000", 0) == 0; }),
              1);  // the thread, once
    const auto cut_start = std::find(thread_end + 1, log.end(), "M400");
    std::vector<std::string> fibre_pieces;
    for (auto it = thread_end + 1; it != cut_start; ++it)
        if (it->rfind("G1 E", 0) == 0) fibre_pieces.push_back(*it);
    EXPECT_EQ(fibre_pieces, std::vector<std::string>(all.begin() + done_before, all.end()));
    EXPECT_EQ(engine_->status().stats.feed_left_at_cut, 0u);
    // A rethread names the run's first event.
    EXPECT_THROW(SyncEngine(program_, extruder_, board_, *robot_,
                            SyncOptions{.first_event = 7, .resume_feed = {{6, 1, true}}}),
                 std::invalid_argument);
}

TEST_F(SyncFaultTest, AResumeFeedOnAnEventWithoutFeedIsRefused) {
    boot();
    SyncOptions o;
    o.first_event = 7;
    o.resume_feed = daemon::sync::ResumeFeed{3, 0};  // event 3 is extrude_off
    EXPECT_THROW(SyncEngine(program_, extruder_, board_, *robot_,
                            SyncOptions{.first_event = 2, .resume_feed = {{5, 0}}}),
                 std::invalid_argument);  // not before first_event
    start_engine(o);
    ASSERT_TRUE(eventually([&] { return engine_->status().faulted; }));
    EXPECT_THAT(engine_->status().fault_reason,
                HasSubstr("resume: event 3 (extrude_off) does not start a metered path"));
}
