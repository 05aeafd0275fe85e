// MarlinProtocol (the host protocol state machine, no I/O) driven with exact transcripts: the
// lines it writes, to the byte, for what the firmware answers, in the spellings Marlin 1.1.9 and
// 2.x print (marlin-notes 1.2-1.5). Time is a hand-made clock: nothing here waits.
#include "drivers/marlin/marlin_protocol.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace fibrecell::drivers::marlin;
using ::testing::ElementsAre;
using ::testing::IsEmpty;

namespace {

class MarlinProtocolTest : public ::testing::Test {
  protected:
    // A protocol on `settings` whose session starts at line `first`; its M110 is acknowledged
    // and forgotten, so that written() starts with the job's first line.
    void start(ProtocolSettings settings = {}, std::int64_t first = 11) {
        protocol_ = std::make_unique<MarlinProtocol>(
            settings, MarlinProtocol::Hooks{
                          .write = [this](std::string_view b) { written_.emplace_back(b); },
                          .acked = [this](std::int64_t line) { acked_.push_back(line); },
                          .failed =
                              [this](LinkFailure f, const std::string& detail) {
                                  failures_.push_back(f);
                                  detail_ = detail;
                              },
                          .observed = nullptr});
        protocol_->begin_session(first, at(0));
        ASSERT_THAT(take_written(), ElementsAre("N" + std::to_string(first) + " M110 N" +
                                                std::to_string(first) + "*125\n"));
        reply("ok", 0);
        ASSERT_THAT(acked_, ElementsAre(first));
        ASSERT_TRUE(protocol_->session_synced());
        acked_.clear();
    }

    static Clock::time_point at(double s) {
        return Clock::time_point{} + std::chrono::hours(1) +
               std::chrono::duration_cast<Clock::duration>(Seconds(s));
    }
    void reply(std::string_view line, double s) { protocol_->on_line(line, at(s)); }
    void tick(double s) { protocol_->on_tick(at(s)); }
    std::int64_t send(std::string_view command, double s = 0) { return protocol_->enqueue(command, at(s)); }

    // The bytes written since the last call, one entry per write.
    std::vector<std::string> take_written() {
        std::vector<std::string> out;
        out.swap(written_);
        return out;
    }

    std::unique_ptr<MarlinProtocol> protocol_;
    std::vector<std::string> written_;
    std::vector<std::int64_t> acked_;
    std::vector<LinkFailure> failures_;
    std::string detail_;
};

TEST_F(MarlinProtocolTest, ASessionStartsWithTheNumberedResetAndNothingElseUntilItsOk) {
    ProtocolSettings s;
    s.window_lines = 3;
    MarlinProtocol p(s, {.write = [this](std::string_view b) { written_.emplace_back(b); },
                         .acked = [this](std::int64_t line) { acked_.push_back(line); },
                         .failed = nullptr,
                         .observed = nullptr});
    p.begin_session(0, at(0));
    EXPECT_EQ(p.enqueue("G28 ; home first", at(0)), 1);
    EXPECT_EQ(p.enqueue("T1", at(0)), 2);
    EXPECT_THAT(take_written(), ElementsAre("N0 M110 N0*125\n"));  // the reset goes alone
    EXPECT_FALSE(p.session_synced());
    p.on_line("ok", at(0.01));
    EXPECT_TRUE(p.session_synced());
    EXPECT_THAT(take_written(), ElementsAre("N1 G28*18\n", "N2 T1*57\n"));
    EXPECT_THAT(acked_, ElementsAre(0));
}

TEST_F(MarlinProtocolTest, OneLineInFlightEachOkSendsTheNext) {
    start();
    EXPECT_EQ(send("G1 E1.000 F300"), 12);
    EXPECT_EQ(send("M400"), 13);
    EXPECT_EQ(send("M42 P11 S0 (cutter open)"), 14);
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    EXPECT_EQ(protocol_->in_flight(), 1u);
    EXPECT_EQ(protocol_->queued(), 3u);
    reply("ok", 0.1);
    EXPECT_THAT(take_written(), ElementsAre("N13 M400*21\n"));
    reply("ok", 0.2);
    EXPECT_THAT(take_written(), ElementsAre("N14 M42 P11 S0*19\n"));
    reply("ok", 0.3);
    EXPECT_THAT(take_written(), IsEmpty());
    EXPECT_THAT(acked_, ElementsAre(12, 13, 14));
    EXPECT_EQ(protocol_->queued(), 0u);
    EXPECT_EQ(protocol_->stats().lines_sent, 4u);  // with the M110
    EXPECT_THAT(failures_, IsEmpty());
}

TEST_F(MarlinProtocolTest, ResendFollowedByOkAsMarlin119PrintsItGoesBackOnce) {
    start();
    send("G1 E1.000 F300");
    send("M400");
    take_written();
    // Marlin 1.1.9 gcode_line_error(): the error, then flush_and_request_resend(): Resend + ok.
    reply("Error:checksum mismatch, Last Line: 11", 0.1);
    reply("Resend: 12", 0.1);
    EXPECT_THAT(take_written(), IsEmpty()) << "detect: held for the ok that may follow";
    reply("ok", 0.1);
    EXPECT_EQ(protocol_->resend_ok_detected(), std::optional<bool>(true));
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    EXPECT_THAT(acked_, IsEmpty()) << "the Resend's ok acknowledges nothing";
    reply("ok", 0.2);
    EXPECT_THAT(acked_, ElementsAre(12));
    EXPECT_THAT(take_written(), ElementsAre("N13 M400*21\n"));
    reply("ok", 0.3);
    EXPECT_THAT(acked_, ElementsAre(12, 13));
    EXPECT_EQ(protocol_->stats().resend_requests, 1u);
    EXPECT_THAT(failures_, IsEmpty());

    // Learned: the next Resend's ok is expected at once, and the line goes straight back.
    send("G1 E1.000 F300");
    EXPECT_THAT(take_written(), ElementsAre("N14 G1 E1.000 F300*2\n"));
    reply("Resend: 14", 0.4);
    EXPECT_THAT(take_written(), ElementsAre("N14 G1 E1.000 F300*2\n"));
    reply("ok", 0.4);  // the Resend's
    EXPECT_THAT(acked_, ElementsAre(12, 13));
    reply("ok", 0.5);
    EXPECT_THAT(acked_, ElementsAre(12, 13, 14));
}

TEST_F(MarlinProtocolTest, ResendWithoutOkIsResentWhenTheOkWaitRunsOut) {
    start();
    send("G1 E1.000 F300");
    take_written();
    reply("Resend:12", 1.0);  // older firmware: no space, no ok after it
    tick(1.4);
    EXPECT_THAT(take_written(), IsEmpty());
    tick(1.5);
    EXPECT_EQ(protocol_->resend_ok_detected(), std::optional<bool>(false));
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    reply("ok", 1.6);
    EXPECT_THAT(acked_, ElementsAre(12));
    EXPECT_THAT(failures_, IsEmpty());
}

TEST_F(MarlinProtocolTest, ResendOkNeverResendsAtOnceAndAlwaysConsumesTheOk) {
    ProtocolSettings never;
    never.resend_ok = ResendOk::never;
    start(never);
    send("G1 E1.000 F300");
    take_written();
    reply("rs N12", 0.1);  // Repetier's spelling
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    reply("ok", 0.2);
    EXPECT_THAT(acked_, ElementsAre(12));

    ProtocolSettings always;
    always.resend_ok = ResendOk::always;
    acked_.clear();
    start(always, 0);
    send("G28");
    take_written();
    reply("Resend: 1", 0.1);
    EXPECT_THAT(take_written(), ElementsAre("N1 G28*18\n"));
    reply("ok", 0.1);
    EXPECT_THAT(acked_, IsEmpty());
    reply("ok", 0.2);
    EXPECT_THAT(acked_, ElementsAre(1));
}

TEST_F(MarlinProtocolTest, ACorruptedLineWithOthersInFlightGoesBackOnceAndTheirRequestsAreIgnored) {
    ProtocolSettings s;
    s.window_lines = 3;
    start(s, 9);
    send("G1 E0.5 F300");
    send("G1 E0.6 F300");
    send("G1 E0.7 F300");
    EXPECT_THAT(take_written(),
                ElementsAre("N10 G1 E0.5 F300*2\n", "N11 G1 E0.6 F300*0\n", "N12 G1 E0.7 F300*2\n"));
    // N10 arrived corrupted; N11 and N12 then fail the sequence check, each drawing a request.
    reply("Error:checksum mismatch, Last Line: 9", 0.1);
    reply("Resend: 10", 0.1);
    reply("ok", 0.1);
    EXPECT_THAT(take_written(),
                ElementsAre("N10 G1 E0.5 F300*2\n", "N11 G1 E0.6 F300*0\n", "N12 G1 E0.7 F300*2\n"));
    for (int i = 0; i < 2; ++i) {
        reply("Error:Line Number is not Last Line Number+1, Last Line: 9", 0.1);
        reply("Resend: 10", 0.1);
        reply("ok", 0.1);
    }
    EXPECT_THAT(take_written(), IsEmpty());
    EXPECT_EQ(protocol_->stats().resends_ignored, 2u);
    reply("ok", 0.2);
    reply("ok", 0.2);
    reply("ok", 0.2);
    EXPECT_THAT(acked_, ElementsAre(10, 11, 12));
    EXPECT_EQ(protocol_->in_flight(), 0u);
    EXPECT_EQ(protocol_->stats().unexpected_oks, 0u);
    EXPECT_THAT(failures_, IsEmpty());
}

// Marlin 1.1.9's flush_and_request_resend() empties its RX buffer first: lines in flight behind
// the bad one that were already in it vanish and draw no request of their own. The resent line
// corrupted again is then a new request, not one of those that never came.
TEST_F(MarlinProtocolTest, AResentLineCorruptedAgainIsResentAfterTheFirmwareFlushedTheOthers) {
    ProtocolSettings s;
    s.window_lines = 3;
    s.resend_ok = ResendOk::always;
    start(s, 9);
    send("G1 E0.5 F300");
    send("G1 E0.6 F300");
    send("G1 E0.7 F300");
    const std::vector<std::string> all = {"N10 G1 E0.5 F300*2\n", "N11 G1 E0.6 F300*0\n",
                                          "N12 G1 E0.7 F300*2\n"};
    EXPECT_EQ(take_written(), all);
    reply("Error:checksum mismatch, Last Line: 9", 0.1);  // N11 and N12 flushed with it
    reply("Resend: 10", 0.1);
    reply("ok", 0.1);
    EXPECT_EQ(take_written(), all);
    reply("Error:checksum mismatch, Last Line: 9", 0.2);  // the copy of N10, corrupted too
    reply("Resend: 10", 0.2);
    reply("ok", 0.2);
    EXPECT_EQ(take_written(), all);
    reply("ok", 0.3);
    reply("ok", 0.3);
    reply("ok", 0.3);
    EXPECT_THAT(acked_, ElementsAre(10, 11, 12));
    EXPECT_THAT(failures_, IsEmpty());
}

TEST_F(MarlinProtocolTest, BusyLinesKeepALongCommandAliveAndSilenceAfterThemProbes) {
    ProtocolSettings s;
    s.long_timeout = Seconds(2.0);
    start(s, 0);
    send("G28");
    EXPECT_THAT(take_written(), ElementsAre("N1 G28*18\n"));
    for (double t : {1.5, 3.0, 4.5}) {
        reply("echo:busy: processing", t);
        tick(t + 0.4);
    }
    tick(6.4);  // 1.9 s after the last busy line
    EXPECT_THAT(take_written(), IsEmpty());
    EXPECT_EQ(protocol_->stats().timeouts, 0u);
    tick(6.6);  // 2.1 s: the ok is overdue, the same numbered line goes again
    EXPECT_THAT(take_written(), ElementsAre("N1 G28*18\n"));
    EXPECT_EQ(protocol_->stats().timeouts, 1u);
    // The firmware had it (its ok was lost): the copy fails the sequence check and never runs.
    reply("Error:Line Number is not Last Line Number+1, Last Line: 1", 6.7);
    reply("Resend: 2", 6.7);
    reply("ok", 6.7);
    EXPECT_THAT(acked_, ElementsAre(1));
    send("T1", 6.8);
    EXPECT_THAT(take_written(), ElementsAre("N2 T1*57\n"));
    EXPECT_THAT(failures_, IsEmpty());
}

TEST_F(MarlinProtocolTest, HeatingHasNoOkDeadlineOnlyLiveness) {
    ProtocolSettings s;
    s.heating_liveness = Seconds(10.0);
    start(s, 0);
    send("M109 S200");
    EXPECT_THAT(take_written(), ElementsAre("N1 M109 S200*107\n"));
    for (int t = 1; t <= 60; ++t) {  // a minute of heat-up reports: no probe, no failure
        reply(" T:" + std::to_string(20 + 3 * t) + ".0 /200.0 B:22.0 /0.0 @:127 W:?", t);
        tick(t + 0.5);
    }
    EXPECT_THAT(take_written(), IsEmpty());
    EXPECT_THAT(failures_, IsEmpty());
    reply("ok", 61);
    EXPECT_THAT(acked_, ElementsAre(1));

    send("M109 S210", 62);
    take_written();
    tick(72.1);
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::heating_stalled));
}

TEST_F(MarlinProtocolTest, AMissingOkIsProbedThenTheLinkFails) {
    ProtocolSettings s;
    s.motion_timeout = Seconds(1.0);
    s.max_probes = 2;
    s.silence_timeout = Seconds(100.0);
    start(s);
    send("G1 E1.000 F300");
    take_written();
    tick(1.0);
    EXPECT_THAT(take_written(), IsEmpty());
    tick(1.1);
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    tick(2.2);
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    tick(3.3);
    EXPECT_THAT(take_written(), IsEmpty());
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::ack_timeout));
    EXPECT_EQ(detail_, "no ok for line 12 (motion) after 2 probes");
    EXPECT_EQ(protocol_->stats().timeouts, 3u);
    reply("ok", 3.4);  // after a failure nothing more happens
    EXPECT_THAT(acked_, IsEmpty());
}

TEST_F(MarlinProtocolTest, ALateOkAfterAProbeAndTheCopysRejectionRunNothingTwice) {
    ProtocolSettings s;
    s.motion_timeout = Seconds(1.0);
    start(s);
    send("G1 E1.000 F300");
    send("M400");
    take_written();
    tick(1.1);
    EXPECT_THAT(take_written(), ElementsAre("N12 G1 E1.000 F300*4\n"));
    reply("ok", 1.2);  // the original's, late
    EXPECT_THAT(acked_, ElementsAre(12));
    EXPECT_THAT(take_written(), IsEmpty()) << "waits for the copy's late reply";
    reply("Error:Line Number is not Last Line Number+1, Last Line: 12", 1.25);
    reply("Resend: 13", 1.25);
    reply("ok", 1.25);
    EXPECT_THAT(take_written(), ElementsAre("N13 M400*21\n"));
    reply("ok", 1.3);
    EXPECT_THAT(acked_, ElementsAre(12, 13));
    EXPECT_EQ(protocol_->stats().unexpected_oks, 0u);
    EXPECT_THAT(failures_, IsEmpty());
}

TEST_F(MarlinProtocolTest, AResendForALineNeverSentFailsTheLink) {
    start();
    send("G1 E1.000 F300");
    take_written();
    reply("Resend: 40", 0.1);
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::resend_out_of_window));
    EXPECT_EQ(detail_, "the firmware asked for line 40 but only lines 12..12 are unacknowledged");
    EXPECT_THAT(take_written(), IsEmpty());
}

TEST_F(MarlinProtocolTest, AResendForALineAlreadyAcknowledgedFailsTheLink) {
    start();
    send("G1 E1.000 F300");
    reply("ok", 0.1);
    send("M400");
    take_written();
    reply("Resend: 12", 0.2);
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::resend_out_of_window));
    EXPECT_EQ(detail_, "the firmware asked for line 12 but only lines 13..13 are unacknowledged");
}

TEST_F(MarlinProtocolTest, AnOkNobodyWaitsForIsCountedAndIgnored) {
    start();
    reply("ok", 0.1);
    EXPECT_EQ(protocol_->stats().unexpected_oks, 1u);
    send("T1", 0.2);
    EXPECT_THAT(take_written(), ElementsAre("N12 T1*8\n"));
    reply("ok", 0.3);
    EXPECT_THAT(acked_, ElementsAre(12));
    EXPECT_THAT(failures_, IsEmpty());
}

TEST_F(MarlinProtocolTest, ABoardResetMidJobFailsItAndNothingIsRenumbered) {
    start();
    send("G1 E1.000 F300");
    send("M400");
    take_written();
    reply("ok", 0.1);
    take_written();
    reply("\xff\xff", 0.2);  // line noise of the reset
    reply("start", 0.3);
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::firmware_reset));
    EXPECT_TRUE(protocol_->seen_start());
    reply("echo: External Reset", 0.3);
    reply("ok", 0.4);
    send("T1", 0.5);
    EXPECT_THAT(take_written(), IsEmpty());
    EXPECT_THAT(acked_, ElementsAre(12));
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::firmware_reset));
}

// The reset cut the firmware's `ok` for line 13 short: that line was taken (its feed is the
// board's queue, lost with the reset), and the session fails as on any reset.
TEST_F(MarlinProtocolTest, ABoardResetThatCutsAnOkShortAcknowledgesItsLineAndFailsTheSession) {
    start();
    send("G1 E1.000 F300");
    send("G1 E2.000 F300");
    take_written();
    reply("ok", 0.1);
    reply("ok T:25.5 /0.0 T0:2start", 0.2);
    EXPECT_THAT(acked_, ElementsAre(12, 13));
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::firmware_reset));
}

TEST_F(MarlinProtocolTest, AResendLoopOnOneLineFails) {
    ProtocolSettings s;
    s.resend_ok = ResendOk::always;
    s.max_consecutive_resends = 3;
    start(s);
    send("G1 E1.000 F300");
    take_written();
    for (int i = 0; i < 3; ++i) {
        reply("Error:checksum mismatch, Last Line: 11", 0.1);
        reply("Resend: 12", 0.1);
        reply("ok", 0.1);
    }
    EXPECT_EQ(take_written().size(), 3u);
    EXPECT_THAT(failures_, IsEmpty());
    reply("Resend: 12", 0.2);
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::resend_loop));
    EXPECT_EQ(detail_, "line 12 requested 4 times in a row");
}

TEST_F(MarlinProtocolTest, EmergencyCommandsGoAheadOfTheQueueUnnumbered) {
    start();
    send("G1 E1.000 F300");
    send("M400");
    take_written();
    protocol_->send_emergency("M108");
    EXPECT_THAT(take_written(), ElementsAre("M108\n"));
    reply("ok", 0.1);  // the line's
    reply("ok", 0.1);  // M108's: pays for no line
    EXPECT_THAT(acked_, ElementsAre(12));
    EXPECT_THAT(take_written(), ElementsAre("N13 M400*21\n"));
    protocol_->send_emergency("M112");
    EXPECT_THAT(take_written(), ElementsAre("M112\n"));
    EXPECT_THAT(failures_, ElementsAre(LinkFailure::emergency_stop));
}

}  // namespace
