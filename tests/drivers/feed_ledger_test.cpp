// The ledger reads E as Marlin does: per selected extruder, relative or absolute, G92 resets.
#include "drivers/marlin/feed_ledger.hpp"

#include <gtest/gtest.h>

using fibrecell::drivers::marlin::FeedLedger;

namespace {

FeedLedger after(std::initializer_list<const char*> commands) {
    FeedLedger l;
    for (const char* c : commands) l.taken(c);
    return l;
}

}  // namespace

TEST(FeedLedger, RelativeMovesChargeTheSelectedExtruderAndRetractionsCountBack) {
    const FeedLedger l = after({"M83", "T1", "G1 E42 F600", "G1 E10.5 F1200", "T0", "G1 E3",
                                "G1 E-1.2 F2400", "G1 E1.2 F2400", "G1 X10 Y5 F3000"});
    EXPECT_DOUBLE_EQ(l.totals().of(0), 3.0);
    EXPECT_DOUBLE_EQ(l.totals().of(1), 52.5);
    EXPECT_DOUBLE_EQ(l.totals().of(2), 0.0);
}

TEST(FeedLedger, AbsoluteMovesChargeTheDifferenceFromG92) {
    // Marlin boots absolute: E is a position until M83.
    const FeedLedger l = after({"G1 E5", "G1 E8", "G92 E0", "G1 E2", "M83", "G1 E1"});
    EXPECT_DOUBLE_EQ(l.totals().of(0), 11.0);
}

TEST(FeedLedger, ParametersThatLookLikeToolsOrFeedAreNotMoves) {
    // M104 T1 heats E1 without selecting it; M92 E sets steps; M203 E a limit.
    const FeedLedger l = after({"M83", "M104 T1 S250", "M109 T1 S250", "M92 E400", "M203 E50",
                                "G1 E2", "T9", "G1 E1"});
    EXPECT_DOUBLE_EQ(l.totals().of(0), 3.0);
    EXPECT_DOUBLE_EQ(l.totals().of(1), 0.0);
    EXPECT_FALSE(FeedLedger::counts("M104 T1 S250"));
    EXPECT_FALSE(FeedLedger::counts("G1 X5 F300"));
    EXPECT_TRUE(FeedLedger::counts("g1 e5"));
    EXPECT_TRUE(FeedLedger::counts("T1"));
}

TEST(FeedLedger, AColdExtrusionRefusalMovesThePositionButFeedsNothing) {
    FeedLedger l;
    l.taken("G1 E5", false);  // absolute: the firmware's position is 5 all the same
    l.taken("G1 E7");
    EXPECT_DOUBLE_EQ(l.totals().of(0), 2.0);
}

TEST(FeedLedger, AFirmwareRestartIsBackOnT0AbsoluteAndKeepsTheTotals) {
    FeedLedger l = after({"M83", "T1", "G1 E4"});
    l.firmware_started();
    l.taken("G1 E6");  // absolute again, on T0
    l.taken("G1 E6");
    EXPECT_DOUBLE_EQ(l.totals().of(1), 4.0);
    EXPECT_DOUBLE_EQ(l.totals().of(0), 6.0);
}
