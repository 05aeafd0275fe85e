// The robot's 16-bit event counter back to sequence numbers: progress, gaps, duplicates, the
// 65535 -> 0 wrap, the run-request reset and steps back.
#include "daemon/sync/event_counter.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::daemon::sync;

namespace {

void expect_step(const CounterAdvance& a, CounterStep step, std::int64_t from, std::int64_t to) {
    EXPECT_EQ(a.step, step);
    EXPECT_EQ(a.from, from);
    EXPECT_EQ(a.to, to);
}

}  // namespace

TEST(EventCounter, ForwardGapAndDuplicate) {
    EventCounter c(0);
    expect_step(c.advance(0), CounterStep::duplicate, 0, 0);  // the run request's 0 on a fresh run
    expect_step(c.advance(1), CounterStep::forward, 0, 1);
    expect_step(c.advance(2), CounterStep::forward, 1, 2);
    expect_step(c.advance(2), CounterStep::duplicate, 2, 2);
    expect_step(c.advance(5), CounterStep::forward, 2, 5);  // 3 and 4 were missed
    EXPECT_EQ(c.last(), 5);
}

TEST(EventCounter, WrapsPast65535) {
    EventCounter c(65534);
    expect_step(c.advance(65535), CounterStep::forward, 65534, 65535);
    expect_step(c.advance(0), CounterStep::forward, 65535, 65536);
    expect_step(c.advance(3), CounterStep::forward, 65536, 65539);
    expect_step(c.advance(65535), CounterStep::backwards, 65539, 65535);
    EXPECT_EQ(c.last(), 65539);  // a step back does not move the baseline
    // The largest forward step, 32767, across the second wrap: 131070 is raw 65534.
    EventCounter far(131070);
    expect_step(far.advance(32765), CounterStep::forward, 131070, 131070 + 32767);
}

TEST(EventCounter, StepBackIsReported) {
    EventCounter c(0);
    c.advance(3);
    expect_step(c.advance(2), CounterStep::backwards, 3, 2);
    // Half the counter range ahead counts as behind: 3 + 32768 is taken as 32768 events back.
    expect_step(c.advance(3 + 32768), CounterStep::backwards, 3, 3 - 32768);
    expect_step(c.advance(0), CounterStep::backwards, 3, 0);  // 0 after progress is no reset
}

TEST(EventCounter, ZeroBeforeProgressIsTheRunRequestOnResume) {
    EventCounter c(57);  // resumed after event 57
    expect_step(c.advance(0), CounterStep::reset, 57, 57);
    expect_step(c.advance(58), CounterStep::forward, 57, 58);
    EventCounter near_wrap(65533);  // 0 would be 3 ahead, but no event came yet
    expect_step(near_wrap.advance(0), CounterStep::reset, 65533, 65533);
    expect_step(near_wrap.advance(65534), CounterStep::forward, 65533, 65534);
}
