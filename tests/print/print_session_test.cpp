// Printing end to end in simulation, every driver real (print_cell_fixture.hpp): a job's exact
// board log at time scale 20; a pause in the middle of a fibre path; the Modbus link dropped mid-print and the job resumed;
// 1% corrupted serial lines; a chunk that does not build, refused before anything moves.
#include "print_cell_fixture.hpp"

#include <gmock/gmock.h>

using namespace fibrecell;
using namespace fibrecell::test;
using ::testing::HasSubstr;

namespace {

// PLA square, two fibre lines, PLA square, two fibre lines: 4 cuts, 2 PLA paths.
abb::PrintProgram four_cut_program() {
    return make_program({pla_square(0, 0.8), fibre_lines(1, 0.85, 2), pla_square(2, 1.65),
                         fibre_lines(3, 1.7, 2)});
}

// The fibre's G1 E pieces of the job's first fibre path: between its threading M400 (the first
// M400 of the job) and its cut's.
std::vector<std::string> first_fibre_pieces(const std::vector<std::string>& log) {
    const auto thread_end = std::find(log.begin(), log.end(), "M400");
    const auto cut_start = std::find(thread_end == log.end() ? log.end() : thread_end + 1, log.end(), "M400");
    std::vector<std::string> out;
    for (auto it = thread_end; it != cut_start && it != log.end(); ++it)
        if (it->rfind("G1 E", 0) == 0) out.push_back(*it);
    return out;
}

}  // namespace

TEST_F(PrintCellTest, AFourCutJobRunsTheExactBoardLogAtTimeScale20) {
    const abb::PrintProgram program = four_cut_program();
    make_session(program, chunks_of(program), options());
    session_->start();
    ASSERT_EQ(session_->wait_until_done(120s), PrintPhase::completed) << session_->poll().reason;
    EXPECT_EQ(executed_job(), expected_board_log(program));
}

TEST_F(PrintCellTest, PauseInTheMiddleOfAFibrePathLosesAndRepeatsNoFeed) {
    const abb::PrintProgram program = make_program({pla_square(0, 0.8), fibre_lines(1, 0.85, 1)});
    make_session(program, chunks_of(program), options());
    session_->start();
    ASSERT_TRUE(metering(first_of(program, EventKind::fibre_start), 15));
    session_->pause();
    // The robot brakes and stands; the feed stops with it.
    ASSERT_TRUE(eventually([&] { return !cell().motion_status().moving; }));
    const auto sent = session_->poll().sync.metering.pieces_sent;
    const auto where = cell().robot().path_mm;
    // 6 simulated s later (30 mm of path if it went on):
    const double paused_at_s = cell().clock().now_s();
    ASSERT_TRUE(eventually([&] { return cell().clock().now_s() >= paused_at_s + 6.0; }));
    EXPECT_EQ(session_->poll().sync.metering.pieces_sent, sent);
    EXPECT_NEAR(cell().robot().path_mm, where, 1e-9);
    session_->resume();
    ASSERT_EQ(session_->wait_until_done(60s), PrintPhase::completed) << session_->poll().reason;
    const auto log = executed_job();
    EXPECT_EQ(log, expected_board_log(program));
    EXPECT_EQ(first_fibre_pieces(log), metered_pieces(58, 1.0, ccf_speed, 1));
}

TEST_F(PrintCellTest, ModbusLinkDroppedMidPrintHoldsTheRobotAndTheJobResumes) {
    const abb::PrintProgram program = make_program({pla_square(0, 0.8), fibre_lines(1, 0.85, 1)});
    make_session(program, chunks_of(program), options());
    session_->start();
    ASSERT_TRUE(metering(first_of(program, EventKind::fibre_start), 10));
    cell().drop_modbus_link(1500ms);
    // The service side: a fault with its reason; the robot side: FcMain holds on the lost
    // heartbeat and the robot stands.
    ASSERT_TRUE(eventually([&] { return session_->poll().phase == PrintPhase::faulted; }));
    EXPECT_THAT(session_->poll().reason, HasSubstr("robot I/O"));
    ASSERT_TRUE(eventually([&] {
        return !cell().motion_status().moving &&
               abb::FcMainControl(rws()).status().state == abb::FcState::held;
    })) << "FcMain: " << abb::to_string(abb::FcMainControl(rws()).status().state);

    ASSERT_TRUE(robot().wait_until_up(10s));
    session_->resume();
    const auto phase = session_->wait_until_done(60s);
    std::string task_log;
    for (const auto& e : cell().task_log()) task_log += e.text + "\n";
    ASSERT_EQ(phase, PrintPhase::completed) << session_->poll().reason << "\nengine: "
                                            << session_->poll().sync.fault_reason << "\nRAPID:\n"
                                            << task_log;
    // Nothing fed twice across the fault, and what was not fed is accounted for: the robot ran on
    // until FcMain's heartbeat time-out held it, so the cut may come before the rest of the feed.
    const auto pieces = first_fibre_pieces(executed_job());
    const auto all = metered_pieces(58, 1.0, ccf_speed, 1);
    ASSERT_LE(pieces.size(), all.size());
    EXPECT_TRUE(std::equal(pieces.begin(), pieces.end(), all.begin()));
    double fed = 0;
    for (const auto& p : pieces) fed += std::stod(p.substr(4));
    EXPECT_NEAR(fed + session_->poll().sync.stats.feed_left_at_cut_mm, 58.0, 1e-6);
    // What was not fed is the path's shortfall, kept by the session across the engine the resume
    // replaced.
    const auto stats = session_->poll().sync.stats;
    if (stats.feed_left_at_cut_mm > 0.05) {
        ASSERT_FALSE(stats.shortfalls.empty());
        EXPECT_EQ(stats.shortfalls.front().kind, daemon::sync::ShortfallKind::fibre_feed_dropped);
        EXPECT_EQ(stats.shortfalls.front().sequence, first_of(program, EventKind::fibre_start));
        EXPECT_DOUBLE_EQ(stats.shortfalls.front().mm, stats.feed_left_at_cut_mm);
    }
}

TEST_F(PrintCellTest, OnePercentCorruptedSerialLinesLeaveTheBoardLogIdentical) {
    const abb::PrintProgram program = make_program({pla_square(0, 0.8), fibre_lines(1, 0.85, 1)});
    const auto expected = expected_board_log(program);
    const std::int64_t first = *mock().executed().back().line + 1;
    const auto lines = static_cast<std::int64_t>(expected.size());
    for (std::int64_t k = first + 7; k < first + lines; k += 100) mock().corrupt_line(k);
    make_session(program, chunks_of(program), options());
    session_->start();
    ASSERT_EQ(session_->wait_until_done(60s), PrintPhase::completed) << session_->poll().reason;
    EXPECT_EQ(executed_job(), expected);
    EXPECT_GE(board().stats().resend_requests, static_cast<std::uint64_t>(lines / 100));
}

TEST_F(PrintCellTest, AChunkThatDoesNotBuildIsRefusedBeforeAnythingMoves) {
    const abb::PrintProgram program = four_cut_program();
    auto chunks = chunks_of(program);
    ASSERT_GE(chunks.size(), 2u);
    auto& text = chunks[1].text;
    const auto at = text.find("MoveL");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 5, "MoveX");
    make_session(program, chunks, options());
    try {
        session_->start();
        FAIL() << "a broken chunk was accepted";
    } catch (const daemon::print::PrintError& e) {
        EXPECT_THAT(e.what(), HasSubstr("pre-flight: " + chunks[1].file_name));
    }
    EXPECT_TRUE(executed_job().empty());
    EXPECT_FALSE(cell().motion_status().moving);
    EXPECT_EQ(cell().robot().path_mm, 0);
}
