#include "drivers/marlin/marlin_line.hpp"
#include "drivers/marlin/marlin_reply.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::drivers::marlin;

// Checksums worked out in docs/marlin-link.md, "Numbers and checksums" (the last one also on
// 3dprinting.stackexchange).
TEST(MarlinLine, FramesWithTheChecksumMarlinExpects) {
    EXPECT_EQ(frame_line(0, "M110 N0"), "N0 M110 N0*125");
    EXPECT_EQ(frame_line(1, "G28"), "N1 G28*18");
    EXPECT_EQ(frame_line(2, "T1"), "N2 T1*57");
    EXPECT_EQ(frame_line(3, "M42 P11 S255"), "N3 M42 P11 S255*39");
    EXPECT_EQ(frame_line(10, "G92 X0 Y0 Z0 A0 B0"), "N10 G92 X0 Y0 Z0 A0 B0*107");
}

TEST(MarlinLine, RejectsLinesMarlinWouldTruncateOrMisread) {
    EXPECT_THROW(frame_line(1, "M117 " + std::string(90, 'x')), LineError);
    EXPECT_NO_THROW(frame_line(1, "M117 " + std::string(70, 'x')));
    EXPECT_THROW(frame_line(1, "G1 E1*5"), LineError);
    EXPECT_THROW(frame_line(1, "G1 E1\nG1 E2"), LineError);
}

TEST(MarlinLine, StripsCommentsAndClassifies) {
    EXPECT_EQ(strip_comment("  G1 E5 F300 ; prime (slowly)"), "G1 E5 F300");
    EXPECT_EQ(strip_comment("G1 (feed) E5"), "G1  E5");
    EXPECT_EQ(strip_comment("; only a comment"), "");
    EXPECT_EQ(classify("M109 T1 S250"), CommandClass::heating);
    EXPECT_EQ(classify("M400"), CommandClass::long_running);
    EXPECT_EQ(classify("G4 P100"), CommandClass::long_running);
    EXPECT_EQ(classify("G1 E5 F300"), CommandClass::motion);
    EXPECT_EQ(classify("M42 P11 S255"), CommandClass::normal);
    EXPECT_TRUE(is_emergency("M112"));
    EXPECT_FALSE(is_emergency("M1120"));
}

TEST(MarlinReply, ParsesOkVariants) {
    EXPECT_EQ(parse_reply("ok").kind, ReplyKind::ok);
    const Reply adv = parse_reply("ok N6659 P15 B3");
    EXPECT_EQ(adv.kind, ReplyKind::ok);
    EXPECT_EQ(adv.line, 6659);
    EXPECT_EQ(adv.planner_free, 15);
    EXPECT_EQ(adv.buffer_free, 3);
    const Reply m105 = parse_reply("ok T:210.00 /210.00 B:60.00 /60.00 T0:210.00 /210.00 "
                                   "T1:185.00 /190.00 @:62 B@:30 @0:62 @1:110");
    ASSERT_TRUE(m105.temperatures);
    ASSERT_NE(m105.temperatures->find("T1"), nullptr);
    EXPECT_DOUBLE_EQ(m105.temperatures->find("T1")->actual_c, 185.0);
    EXPECT_DOUBLE_EQ(*m105.temperatures->find("T1")->target_c, 190.0);
    EXPECT_EQ(m105.temperatures->find("@"), nullptr);
}

TEST(MarlinReply, ParsesResendErrorsAndTheRest) {
    EXPECT_EQ(parse_reply("Resend: 124").line, 124);
    EXPECT_EQ(parse_reply("Resend:124").line, 124);
    EXPECT_EQ(parse_reply("rs N124").line, 124);
    EXPECT_EQ(parse_reply("rs N124").kind, ReplyKind::resend);
    const Reply le = parse_reply("Error:Line Number is not Last Line Number+1, Last Line: 41");
    EXPECT_EQ(le.kind, ReplyKind::line_error);
    EXPECT_EQ(le.line, 41);
    EXPECT_EQ(parse_reply("Error:checksum mismatch, Last Line: 7").kind, ReplyKind::line_error);
    EXPECT_TRUE(parse_reply("Error:Printer halted. kill() called!").fatal);
    EXPECT_TRUE(parse_reply("Error:Thermal Runaway, system stopped! Heater_ID: 0").fatal);
    EXPECT_FALSE(parse_reply("Error:Protected Pin").fatal);
    EXPECT_EQ(parse_reply("echo:busy: processing").kind, ReplyKind::busy);
    EXPECT_EQ(parse_reply("busy:processing").kind, ReplyKind::busy);
    EXPECT_EQ(parse_reply(std::string("\0\0\xff\0start", 9)).kind, ReplyKind::start);
    EXPECT_EQ(parse_reply("//action:pause").capability, "pause");
    EXPECT_EQ(parse_reply("//action:start").kind, ReplyKind::action);
}

// A reset while the firmware is sending cuts its line, and `start` follows on the same line (as
// gt2560-avr showed with every position of the cut, from "okstart" to a cut temperature report).
TEST(MarlinReply, AStartAfterALineTheResetCutIsAStart) {
    const Reply cut_ok = parse_reply("ok T:25.5 /0.0 T0:2start");
    EXPECT_EQ(cut_ok.kind, ReplyKind::start);
    EXPECT_EQ(cut_ok.cut_line, "ok T:25.5 /0.0 T0:2");
    EXPECT_EQ(parse_reply("okstart").kind, ReplyKind::start);
    EXPECT_EQ(parse_reply("echo:busy: processstart").cut_line, "echo:busy: process");
    EXPECT_EQ(parse_reply("start").cut_line, "");
    const Reply cap = parse_reply("Cap:EMERGENCY_PARSER:1");
    EXPECT_EQ(cap.capability, "EMERGENCY_PARSER");
    EXPECT_TRUE(cap.capability_on);
    const Reply heat = parse_reply(" T:150.20 /200.00 B:22.10 /0.00 @:127 B@:0 W:?");
    EXPECT_EQ(heat.kind, ReplyKind::temperature);
    EXPECT_FALSE(heat.temperatures->wait_left_s);
    EXPECT_EQ(parse_reply(" T:199.6 /200.0 W:7").temperatures->wait_left_s, 7.0);
    EXPECT_EQ(parse_reply("echo:Unknown command: \"X1\"").kind, ReplyKind::echo);
}
