// Metering one path's feed: pieces that add up exactly, and their pacing against the robot's
// expected position (lead, time scale, pause and resume), with hand-made time points.
#include "daemon/sync/feed_meter.hpp"
#include "daemon/sync/sync_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

using namespace fibrecell::daemon::sync;
using namespace std::chrono_literals;

namespace {

double sum_e(const std::vector<MeterPiece>& pieces) {
    return std::accumulate(pieces.begin(), pieces.end(), 0.0,
                           [](double s, const MeterPiece& p) { return s + p.e_mm; });
}

double ms_after(SteadyClock::time_point t0, SteadyClock::time_point t) {
    return std::chrono::duration<double, std::milli>(t - t0).count();
}

// Pieces of 1 mm over 10 mm at 5 mm/s: piece k ends at k mm, i.e. 0.2 k s into the path.
FeedMeter ten_pieces(SteadyClock::time_point t0, double lead_s, double time_scale = 1) {
    return FeedMeter(split_feed(10, 10, 1), {5, lead_s, time_scale}, t0);
}

}  // namespace

TEST(SplitFeed, EqualPiecesAddUpExactly) {
    const auto pieces = split_feed(58, 58, 1);
    ASSERT_EQ(pieces.size(), 58u);
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        EXPECT_DOUBLE_EQ(pieces[i].path_end_mm, static_cast<double>(i + 1));
        EXPECT_DOUBLE_EQ(pieces[i].e_mm, 1.0);
    }
    // 10 mm of path in 3 pieces of at most 4 mm: E 7 / 3 each, rounded on the running total
    // (2.33333, 4.66667, 7) so the pieces are 2.33333, 2.33334, 2.33333.
    const auto thirds = split_feed(10, 7, 4);
    ASSERT_EQ(thirds.size(), 3u);
    EXPECT_NEAR(thirds[0].e_mm, 2.33333, 1e-12);
    EXPECT_NEAR(thirds[1].e_mm, 2.33334, 1e-12);
    EXPECT_NEAR(thirds[2].e_mm, 2.33333, 1e-12);
    EXPECT_NEAR(thirds[2].path_end_mm, 10, 1e-12);
    EXPECT_NEAR(sum_e(thirds), 7.0, 1e-9);
    // A PLA line: E = path x 0.266..., summed to the rounded total.
    const double ratio = 0.8 * 0.8 / (std::numbers::pi * 1.75 * 1.75 / 4);
    const auto pla = split_feed(80, 80 * ratio, 2);
    EXPECT_EQ(pla.size(), 40u);
    EXPECT_NEAR(sum_e(pla), std::round(80 * ratio * 1e5) / 1e5, 1e-9);
}

TEST(SplitFeed, NothingToFeed) {
    EXPECT_TRUE(split_feed(0, 0, 1).empty());
    EXPECT_TRUE(split_feed(10, 0.000001, 1).empty());  // below the G-code resolution
    EXPECT_THROW(split_feed(10, 10, 0), std::invalid_argument);
}

TEST(FeedMeter, PiecesFallDueLeadAheadOfTheRobot) {
    const auto t0 = SteadyClock::now();
    FeedMeter m = ten_pieces(t0, 0.3);
    // At the start the robot is at 0: pieces ending within 0.3 s x 5 mm/s = 1.5 mm go at once.
    EXPECT_EQ(m.take_due(t0).size(), 1u);
    // Piece 2 ends at 2 mm = 0.4 s of path: due 0.1 s in.
    EXPECT_NEAR(ms_after(t0, *m.next_due()), 100, 1e-3);
    EXPECT_TRUE(m.take_due(t0 + 99ms).empty());
    EXPECT_EQ(m.take_due(t0 + 100ms).size(), 1u);
    // 1 s in the robot is at 5 mm: pieces up to 6.5 mm, i.e. 3..6.
    EXPECT_EQ(m.take_due(t0 + 1s).size(), 4u);
    EXPECT_EQ(m.sent(), 6u);
    EXPECT_DOUBLE_EQ(m.e_sent_mm(), 6.0);
    EXPECT_DOUBLE_EQ(m.e_left_mm(), 4.0);
    EXPECT_EQ(m.take_due(t0 + 10s).size(), 4u);
    EXPECT_FALSE(m.next_due().has_value());
}

TEST(FeedMeter, TimeScaleRunsThePathFaster) {
    const auto t0 = SteadyClock::now();
    FeedMeter m = ten_pieces(t0, 0, 20);
    // Piece k is due at 0.2 k simulated s = 10 k ms real.
    EXPECT_TRUE(m.take_due(t0 + 9ms).empty());
    EXPECT_EQ(m.take_due(t0 + 10ms).size(), 1u);
    EXPECT_EQ(m.take_due(t0 + 100ms).size(), 9u);
}

TEST(FeedMeter, PauseFreezesTheRobotAndResumeContinuesWhereItStopped) {
    const auto t0 = SteadyClock::now();
    FeedMeter m = ten_pieces(t0, 0);
    EXPECT_EQ(m.take_due(t0 + 400ms).size(), 2u);  // robot at 2 mm
    m.pause(t0 + 500ms);                           // robot stopped at 2.5 mm
    EXPECT_FALSE(m.next_due().has_value());
    EXPECT_TRUE(m.take_due(t0 + 5s).empty());
    m.resume(t0 + 5500ms);  // 5 s paused: piece 3 (0.6 s of path) is due at 5.6 s
    EXPECT_NEAR(ms_after(t0, *m.next_due()), 5600, 1e-3);
    EXPECT_TRUE(m.take_due(t0 + 5599ms).empty());
    const auto rest = m.take_due(t0 + 60s);
    ASSERT_EQ(rest.size(), 8u);
    EXPECT_DOUBLE_EQ(rest.front().path_end_mm, 3.0);  // nothing lost, nothing repeated
    EXPECT_DOUBLE_EQ(m.e_sent_mm(), 10.0);
}

TEST(FeedMeter, ResumingSkipsTheFedPiecesAndPacesFromTheirEnd) {
    const auto t0 = SteadyClock::now();
    FeedMeter m = ten_pieces(t0, 0.1);
    const auto resumed_at = t0 + 10s;  // long after the original start: only the skip counts
    m.skip_fed(4, resumed_at);
    EXPECT_EQ(m.sent(), 4u);
    EXPECT_DOUBLE_EQ(m.e_left_mm(), 6);
    // The robot is at 4 mm at resumed_at: piece 5 (ends at 5 mm) is due 0.2 - 0.1 s later.
    ASSERT_TRUE(m.next_due());
    EXPECT_NEAR(ms_after(resumed_at, *m.next_due()), 100, 1e-3);
    const auto due = m.take_due(resumed_at + 100ms);
    ASSERT_EQ(due.size(), 1u);
    EXPECT_DOUBLE_EQ(due[0].path_end_mm, 5);
}

// After an MCU reset the board ran only part of what it took: the rest of that piece is fed
// first, and the robot is where the fed part ends.
TEST(FeedMeter, ResumingInsideAPieceFeedsItsRestFirst) {
    const auto t0 = SteadyClock::now();
    FeedMeter m = ten_pieces(t0, 0.1);
    const auto resumed_at = t0 + 10s;
    m.skip_fed(2.25, resumed_at);
    EXPECT_EQ(m.sent(), 2u);
    EXPECT_DOUBLE_EQ(m.e_sent_mm(), 2.25);
    EXPECT_DOUBLE_EQ(m.e_total_mm(), 10);
    EXPECT_DOUBLE_EQ(m.e_left_mm(), 7.75);
    // The robot at 2.25 mm at resumed_at: piece 3 (its rest, 0.75 mm) ends at 3 mm, due when
    // the robot is 0.1 s of path (0.5 mm) short of it: 0.25 mm later at 5 mm/s.
    ASSERT_TRUE(m.next_due());
    EXPECT_NEAR(ms_after(resumed_at, *m.next_due()), 50, 1e-3);
    const auto due = m.take_due(resumed_at + 60s);
    ASSERT_EQ(due.size(), 8u);
    EXPECT_DOUBLE_EQ(due[0].e_mm, 0.75);
    EXPECT_DOUBLE_EQ(due[0].path_end_mm, 3);
    double fed = 2.25;
    for (const MeterPiece& p : due) fed += p.e_mm;
    EXPECT_NEAR(fed, 10, 1e-9);  // nothing lost, nothing repeated
}

TEST(FeedMeter, ResumingOutsideThePathsFeedIsRefused) {
    FeedMeter m = ten_pieces(SteadyClock::now(), 0.1);
    EXPECT_THROW(m.skip_fed(-0.5, SteadyClock::now()), std::invalid_argument);
    EXPECT_THROW(m.skip_fed(11, SteadyClock::now()), std::invalid_argument);
    FeedMeter nothing_fed = ten_pieces(SteadyClock::now(), 0.1);
    nothing_fed.skip_fed(0, SteadyClock::now());
    EXPECT_EQ(nothing_fed.sent(), 0u);
}

// The lead in real time: 0.3 s of path on the real cell, and at a simulated cell's high time
// scale at least 20 ms of real time (at 120x, 0.3 s of path would be 2.5 ms, less than the host's
// own latencies: the demo's paths ended with feed unsent).
TEST(FeedMeter, AHighTimeScaleKeepsTheLeadAtLeastTwentyRealMilliseconds) {
    SyncOptions o;
    EXPECT_DOUBLE_EQ(effective_lead_s(o), 0.3);
    o.time_scale = 10;
    EXPECT_DOUBLE_EQ(effective_lead_s(o), 0.3);  // 30 ms of real time already
    o.time_scale = 120;
    EXPECT_DOUBLE_EQ(effective_lead_s(o), 2.4);
    // Paced with it at the start of a 10 mm path at 5 mm/s (2 s of path, 16.7 ms of real time at
    // 120x), every piece is within the lead; with the bare 0.3 s only the first (it ends 0.2 s in).
    const auto t0 = SteadyClock::now();
    FeedMeter m = ten_pieces(t0, effective_lead_s(o), o.time_scale);
    EXPECT_EQ(m.take_due(t0).size(), 10u);
    o.min_lead_real_s = 0;
    FeedMeter bare = ten_pieces(t0, effective_lead_s(o), o.time_scale);
    EXPECT_EQ(bare.take_due(t0).size(), 1u);
}
