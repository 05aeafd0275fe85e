// What the board had acknowledged and not yet run at a reset, against hand-worked timelines.
#include "daemon/sync/board_feed_queue.hpp"

#include <gtest/gtest.h>

using namespace std::chrono_literals;
using fibrecell::daemon::sync::BoardFeedQueue;
using fibrecell::daemon::sync::SteadyClock;

TEST(BoardFeedQueue, PiecesTakenTogetherRunOneAfterAnother) {
    const auto t0 = SteadyClock::now();
    BoardFeedQueue q;
    q.acknowledged(1.0, 0.2, t0);  // runs 0-200 ms
    q.acknowledged(1.0, 0.2, t0);  // queued behind it: 200-400 ms
    q.acknowledged(0.5, 0.1, t0);  // 400-500 ms
    EXPECT_DOUBLE_EQ(q.unrun_at(t0), 2.5);
    EXPECT_NEAR(q.unrun_at(t0 + 100ms), 2.0, 1e-9);  // half of the first
    EXPECT_NEAR(q.unrun_at(t0 + 300ms), 1.0, 1e-9);  // half of the second, all of the third
    EXPECT_NEAR(q.unrun_at(t0 + 450ms), 0.25, 1e-9);
    EXPECT_DOUBLE_EQ(q.unrun_at(t0 + 1s), 0.0);
}

TEST(BoardFeedQueue, APieceTakenAfterTheBoardRanDryStartsWhenTaken) {
    const auto t0 = SteadyClock::now();
    BoardFeedQueue q;
    q.acknowledged(1.0, 0.2, t0);
    q.acknowledged(1.0, 0.2, t0 + 500ms);  // idle 200-500 ms: this one runs 500-700 ms
    EXPECT_DOUBLE_EQ(q.unrun_at(t0 + 400ms), 1.0);
    EXPECT_NEAR(q.unrun_at(t0 + 650ms), 0.25, 1e-9);
}

TEST(BoardFeedQueue, NothingAcknowledgedNothingUnrun) {
    EXPECT_DOUBLE_EQ(BoardFeedQueue().unrun_at(SteadyClock::now()), 0.0);
}
