// The percentile helper and the sample window behind the engine's latency statistics.
#include "daemon/sync/latency_stats.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::daemon::sync;
using fibrecell::drivers::abb::EventKind;

TEST(Percentile, NearestRank) {
    EXPECT_EQ(percentile({}, 0.5), 0);
    EXPECT_EQ(percentile({4, 1, 3, 2}, 0.5), 2);
    EXPECT_EQ(percentile({4, 1, 3, 2}, 0.75), 3);
    EXPECT_EQ(percentile({4, 1, 3, 2}, 1.0), 4);
    EXPECT_EQ(percentile({4, 1, 3, 2}, 0.0), 1);
    std::vector<double> hundred;
    for (int i = 100; i >= 1; --i) hundred.push_back(i);
    EXPECT_EQ(percentile(hundred, 0.99), 99);
    EXPECT_EQ(percentile(hundred, 0.5), 50);
}

TEST(SampleWindow, KeepsTheLatestButCountsAll) {
    SampleWindow w(3);
    for (double v : {100.0, 1.0, 2.0, 3.0}) w.add(v);
    const LatencySummary s = w.summary();
    EXPECT_EQ(s.count, 4u);
    EXPECT_EQ(s.median, 2);   // of {1, 2, 3}
    EXPECT_EQ(s.p99, 3);
    EXPECT_EQ(s.max, 100);    // over all samples
}

TEST(EventTimings, PerKindInKindOrder) {
    EventTimings t;
    t.record_submit(EventKind::cut, 2.0, 0.01);
    t.record_submit(EventKind::extrude_on, 1.0, 0.012);
    t.record_ok(EventKind::cut, 5.0);
    const auto s = t.summary();
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].kind, EventKind::extrude_on);
    EXPECT_EQ(s[1].kind, EventKind::cut);
    EXPECT_EQ(s[1].submit_ms.median, 2.0);
    EXPECT_EQ(s[1].ok_ms.max, 5.0);
    EXPECT_EQ(s[1].position_error_mm.max, 0.01);
    EXPECT_EQ(s[0].ok_ms.count, 0u);
}
