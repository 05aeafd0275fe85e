// The robot program of a run that re-enters an interrupted print (daemon/print/print_plan.hpp),
// on a small hand-made program: PLA layer 0 (one square), CCF layer 1 (two straight fibre paths).
// The robot was held inside the interrupted unit, at its layer's height: the run must rise in a
// straight line to the travel height above the unit's start before it comes down there.
#include "daemon/print/print_plan.hpp"

#include "drivers/abb/rapid/rapid_writer.hpp"

#include <gtest/gtest.h>

using namespace fibrecell;
using drivers::abb::EventKind;
using drivers::abb::MoveRole;
using drivers::abb::RobotLayer;

namespace {

class ReentryProgramTest : public ::testing::Test {
  protected:
    void SetUp() override {
        RobotLayer pla{.index = 0, .z = 0.8, .nozzle = drivers::abb::Nozzle::pla};
        pla.paths.push_back(
            {true, {{120, 140}, {140, 140}, {140, 160}, {120, 160}}});
        RobotLayer ccf{.index = 1, .z = 0.85, .nozzle = drivers::abb::Nozzle::ccf};
        for (double y : {145.0, 155.0}) {
            drivers::abb::RobotPath p{false, {}};
            for (int i = 0; i <= 10; ++i) p.points.emplace_back(100 + 10 * i, y);
            ccf.paths.push_back(p);
        }
        program_ = drivers::abb::build_print_program({pla, ccf}, cell_);
    }

    // Checks the run that re-enters after `last_confirmed`; returns it.
    drivers::abb::PrintProgram checked_run(std::int64_t last_confirmed) {
        const daemon::print::ResumePoint r = daemon::print::resume_point(program_, last_confirmed);
        const auto run = daemon::print::reentry_program(program_, r);
        const auto& approach = program_.moves.at(r.first_move);
        EXPECT_EQ(run.moves.size(), program_.moves.size() - r.first_move + 1);
        const auto& rise = run.moves.at(0);
        EXPECT_EQ(rise.role, MoveRole::travel);
        EXPECT_FALSE(rise.joint);
        EXPECT_TRUE(rise.fine);
        // Straight above the path start, the safe height over the part (layer 1 is the top).
        EXPECT_NEAR(rise.position_mm.x(), approach.position_mm.x(), 1e-9);
        EXPECT_NEAR(rise.position_mm.y(), approach.position_mm.y(), 1e-9);
        EXPECT_NEAR(rise.position_mm.z() - approach.position_mm.z(), cell_.motion.safe_height_mm,
                    1e-9);
        EXPECT_EQ(rise.orientation.coeffs(), approach.orientation.coeffs());
        EXPECT_EQ(run.moves.at(1).role, MoveRole::approach);
        EXPECT_EQ(run.moves.at(1).position_mm, approach.position_mm);
        // The run's events start at the unit's first one, on the same moves as in the program.
        EXPECT_FALSE(run.events.empty());
        EXPECT_EQ(run.events.front().sequence, r.first_event);
        for (const auto& e : run.events) {
            const auto& whole = program_.events.at(static_cast<std::size_t>(e.sequence - 1));
            EXPECT_EQ(e.move + r.first_move - 1, whole.move) << "event " << e.sequence;
        }
        EXPECT_NO_THROW(drivers::abb::write_rapid_chunks(run, cell_));
        return run;
    }

    drivers::abb::RobotCellConfig cell_;
    drivers::abb::PrintProgram program_;
};

}  // namespace

TEST_F(ReentryProgramTest, FibrePathInterruptedBeforeItsCutRisesAboveItsStartFirst) {
    // Events: 1 head switch, 2-3 PLA square, 4 layer_end, 5 head switch, 6 fibre_start, 7 cut...
    const auto run = checked_run(6);  // threaded and laying, not cut
    EXPECT_EQ(run.events.front().kind, EventKind::fibre_start);
}

TEST_F(ReentryProgramTest, FirstPathOfTheJobRisesInAStraightLineNotAJointMove) {
    // The program reaches its first path start with a joint move; the run moves linearly.
    ASSERT_TRUE(program_.moves.at(0).joint);
    const auto run = checked_run(1);  // the head switch done, the first square not begun
    EXPECT_EQ(run.events.front().kind, EventKind::extrude_on);
}
