// Where a resumed print re-enters, on a small program built from hand-made toolpaths: PLA layer 0
// (two squares), CCF layer 1 (two straight 100 mm fibre paths), PLA layer 2 (one square). The
// event numbers below are worked out from docs/robot-program.md ("Events"), not read from the
// program: a head switch before the first path and at each change of nozzle, extrude_on/off per
// PLA path, fibre_start/cut/path_end per fibre path, layer_end after each layer's last path.
#include "daemon/print/resume_point.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace fibrecell;
using namespace fibrecell::daemon::print;
using drivers::abb::EventKind;
using drivers::abb::MoveRole;
using drivers::abb::Nozzle;
using drivers::abb::RobotLayer;

namespace {

RobotLayer pla_layer(int index, double z, std::vector<double> x0s) {
    RobotLayer l{.index = index, .z = z, .nozzle = drivers::abb::Nozzle::pla};
    for (double x0 : x0s)
        l.paths.push_back(
            {true, {{x0, 140}, {x0 + 20, 140}, {x0 + 20, 160}, {x0, 160}}});
    return l;
}

RobotLayer fibre_layer(int index, double z, std::vector<double> ys) {
    RobotLayer l{.index = index, .z = z, .nozzle = drivers::abb::Nozzle::ccf};
    for (double y : ys) {
        drivers::abb::RobotPath p{false, {}};
        for (int i = 0; i <= 10; ++i) p.points.emplace_back(100 + 10 * i, y);
        l.paths.push_back(p);
    }
    return l;
}

class ResumePointTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const std::vector<RobotLayer> layers = {pla_layer(0, 0.8, {120, 160}),
                                                   fibre_layer(1, 0.85, {145, 155}),
                                                   pla_layer(2, 1.65, {140})};
        program_ = drivers::abb::build_print_program(layers, drivers::abb::RobotCellConfig{});
    }
    drivers::abb::PrintProgram program_;
};

using V = std::vector<std::int64_t>;

}  // namespace

TEST_F(ResumePointTest, EventNumbersAreTheOnesWorkedOutByHand) {
    const EventKind expected[] = {
        EventKind::head_switch, EventKind::extrude_on,  EventKind::extrude_off,  // 1-3  L0 P0
        EventKind::extrude_on,  EventKind::extrude_off, EventKind::layer_end,    // 4-6  L0 P1
        EventKind::head_switch, EventKind::fibre_start, EventKind::cut,          // 7-9  L1 P0
        EventKind::path_end,    EventKind::fibre_start, EventKind::cut,          // 10-12 L1 P1
        EventKind::path_end,    EventKind::layer_end,   EventKind::head_switch,  // 13-15
        EventKind::extrude_on,  EventKind::extrude_off, EventKind::layer_end};   // 16-18 L2
    ASSERT_EQ(program_.events.size(), std::size(expected));
    for (std::size_t i = 0; i < std::size(expected); ++i)
        EXPECT_EQ(program_.events[i].kind, expected[i]) << "event " << i + 1;
}

TEST_F(ResumePointTest, NothingDoneStartsAtTheFirstLayer) {
    const ResumePoint r = resume_point(program_, 0);
    EXPECT_FALSE(r.nothing_left);
    EXPECT_EQ(r.unit, ResumeUnit::pla_layer);
    EXPECT_EQ(r.layer, 0);
    EXPECT_EQ(r.path, 0);
    EXPECT_EQ(r.first_event, 2);
    EXPECT_EQ(r.done_in_unit, V{});
    EXPECT_EQ(r.fed_again, V{});
    EXPECT_EQ(program_.moves[r.first_move].role, MoveRole::approach);
    EXPECT_EQ(program_.moves[r.first_move].layer, 0);
    EXPECT_EQ(program_.moves[r.first_move].path, 0);
}

TEST_F(ResumePointTest, PlaLayerReentersAtItsStartAndSkipsFinishedPaths) {
    // Path 0 done (3 = its extrude_off), path 1 extruding (4 = its extrude_on) when it stopped.
    const ResumePoint r = resume_point(program_, 4);
    EXPECT_EQ(r.unit, ResumeUnit::pla_layer);
    EXPECT_EQ(r.layer, 0);
    EXPECT_EQ(r.path, 0);
    EXPECT_EQ(r.nozzle, Nozzle::pla);
    EXPECT_EQ(r.first_event, 2);
    EXPECT_EQ(r.done_in_unit, (V{2, 3}));
    EXPECT_EQ(r.fed_again, V{4});  // the interrupted square is extruded again from its start
    for (std::int64_t s : {1, 2, 3}) EXPECT_TRUE(r.done(s)) << s;
    for (std::int64_t s : {4, 5, 6}) EXPECT_FALSE(r.done(s)) << s;
    // Stopped between the two squares: nothing is fed twice.
    const ResumePoint between = resume_point(program_, 3);
    EXPECT_EQ(between.first_event, 2);
    EXPECT_EQ(between.done_in_unit, (V{2, 3}));
    EXPECT_EQ(between.fed_again, V{});
}

TEST_F(ResumePointTest, FinishedLayerGoesOnAtTheNextFibrePath) {
    for (std::int64_t last : {5, 6, 7}) {  // layer 0 fed; its layer_end or the head switch open
        const ResumePoint r = resume_point(program_, last);
        EXPECT_EQ(r.unit, ResumeUnit::fibre_path) << last;
        EXPECT_EQ(r.layer, 1) << last;
        EXPECT_EQ(r.path, 0) << last;
        EXPECT_EQ(r.nozzle, Nozzle::ccf) << last;
        EXPECT_EQ(r.first_event, 8) << last;
        EXPECT_EQ(r.fed_again, V{}) << last;
        EXPECT_EQ(program_.moves[r.first_move].role, MoveRole::approach);
        EXPECT_EQ(program_.moves[r.first_move].layer, 1);
        EXPECT_EQ(program_.moves[r.first_move].path, 0);
    }
}

TEST_F(ResumePointTest, FibrePathInterruptedBeforeItsCutIsLaidAgain) {
    const ResumePoint r = resume_point(program_, 8);  // threaded, laying, not cut
    EXPECT_EQ(r.unit, ResumeUnit::fibre_path);
    EXPECT_EQ(r.layer, 1);
    EXPECT_EQ(r.path, 0);
    EXPECT_EQ(r.first_event, 8);
    EXPECT_EQ(r.fed_again, V{8});
    EXPECT_TRUE(r.cut_first);
    EXPECT_TRUE(r.done(7));
    EXPECT_FALSE(r.done(8));
}

// Each fibre path is 100 mm: 58 mm fed up to the cut, 42 mm (the cutter distance) dragged out.
TEST_F(ResumePointTest, FibreInThePartIsCutFirstAndTheRestLaidFromWhereTheFeedEnded) {
    // Threading not confirmed: the robot never left the path start; nothing to cut.
    EXPECT_FALSE(resume_point(program_, 7).cut_first);
    // Threaded and laying, no feed recorded: cut, then laid again from the start.
    const ResumePoint unknown = resume_point(program_, 8);
    EXPECT_TRUE(unknown.cut_first);
    EXPECT_EQ(unknown.fibre_fed_mm, 0);
    // 20 mm fed: cut, and the rest laid from 20 mm along the path.
    const ResumePoint part = resume_point(program_, 8, FibreFed{8, 20.0});
    EXPECT_TRUE(part.cut_first);
    EXPECT_EQ(part.first_event, 8);
    EXPECT_EQ(part.path, 0);
    EXPECT_DOUBLE_EQ(part.fibre_fed_mm, 20.0);
    // A record of another path does not count.
    EXPECT_EQ(resume_point(program_, 8, FibreFed{11, 20.0}).fibre_fed_mm, 0);
    // Fed up to the cut: the path is done but for the cut made first; the next path follows.
    const ResumePoint all = resume_point(program_, 8, FibreFed{8, 58.0});
    EXPECT_TRUE(all.cut_first);
    EXPECT_EQ(all.path, 1);
    EXPECT_EQ(all.first_event, 11);
    EXPECT_EQ(all.fibre_fed_mm, 0);
    EXPECT_TRUE(all.done(9));
    EXPECT_TRUE(all.done(10));
    // The layer's last path fed up to its cut: the next PLA layer.
    const ResumePoint last = resume_point(program_, 11, FibreFed{11, 58.0});
    EXPECT_TRUE(last.cut_first);
    EXPECT_EQ(last.unit, ResumeUnit::pla_layer);
    EXPECT_EQ(last.first_event, 16);
    // PLA units never cut.
    EXPECT_FALSE(resume_point(program_, 2).cut_first);
    // The program's last path fed up to its cut: nothing left but that cut.
    const drivers::abb::PrintProgram fibre_last = drivers::abb::build_print_program(
        {pla_layer(0, 0.8, {120}), fibre_layer(1, 0.85, {145})}, drivers::abb::RobotCellConfig{});
    std::int64_t start = 0;
    for (const auto& e : fibre_last.events)
        if (e.kind == EventKind::fibre_start) start = e.sequence;
    const ResumePoint end = resume_point(fibre_last, start, FibreFed{start, 58.0});
    EXPECT_TRUE(end.nothing_left);
    EXPECT_TRUE(end.cut_first);
}

TEST_F(ResumePointTest, FibrePathCutIsDoneAndTheNextOneFollows) {
    const ResumePoint r = resume_point(program_, 9);  // cut confirmed, path_end open
    EXPECT_EQ(r.unit, ResumeUnit::fibre_path);
    EXPECT_EQ(r.layer, 1);
    EXPECT_EQ(r.path, 1);
    EXPECT_EQ(r.first_event, 11);
    EXPECT_EQ(r.fed_again, V{});
    EXPECT_TRUE(r.done(10));
    const ResumePoint second = resume_point(program_, 11);
    EXPECT_EQ(second.path, 1);
    EXPECT_EQ(second.first_event, 11);
    EXPECT_EQ(second.fed_again, V{11});
}

TEST_F(ResumePointTest, LastFibrePathCutGoesOnAtTheNextPlaLayer) {
    const ResumePoint r = resume_point(program_, 12);
    EXPECT_EQ(r.unit, ResumeUnit::pla_layer);
    EXPECT_EQ(r.layer, 2);
    EXPECT_EQ(r.path, 0);
    EXPECT_EQ(r.nozzle, Nozzle::pla);
    EXPECT_EQ(r.first_event, 16);
}

TEST_F(ResumePointTest, EverythingFedLeavesNothingAndBadNumbersAreRefused) {
    EXPECT_TRUE(resume_point(program_, 17).nothing_left);  // only layer 2's layer_end open
    EXPECT_TRUE(resume_point(program_, 18).nothing_left);
    EXPECT_TRUE(resume_point(program_, 18).done(18));
    try {
        resume_point(program_, 19);
        FAIL() << "expected an error";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "last confirmed event 19 is outside the program's events 0..18");
    }
    EXPECT_THROW(resume_point(program_, -1), std::invalid_argument);
}
