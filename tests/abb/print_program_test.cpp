// The print program from small hand-made toolpaths (a square, a straight 100 mm fibre path, a PLA
// layer then a CCF layer): move order, positions, tilts, events and their numbers, the cut point,
// the head switch, the idle-nozzle clearance check and point merging. Expected values are worked
// out here from the toolpaths and the configuration, not taken from the program.
#include "drivers/abb/program/print_program.hpp"
#include "drivers/abb/program/point_merge.hpp"
#include "head_tilt.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

using namespace fibrecell;
using namespace fibrecell::drivers::abb;
using fibrecell::test::signed_tilt_deg;

namespace {

using std::numbers::pi;

RobotLayer square_layer(int index, double z, double x0 = 140, double y0 = 140,
                           double side = 20) {
    RobotLayer l{.index = index, .z = z, .nozzle = Nozzle::pla};
    l.paths.push_back({true,
                       {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}}});
    return l;
}

// A straight fibre path of `length` mm along +x from (x0, y0), points every `step` mm.
RobotLayer fibre_layer(int index, double z, double length = 100, double step = 10,
                          double x0 = 100, double y0 = 150) {
    RobotLayer l{.index = index, .z = z, .nozzle = Nozzle::ccf};
    RobotPath p{false, {}};
    const int n = static_cast<int>(std::round(length / step));
    for (int i = 0; i <= n; ++i) p.points.emplace_back(x0 + length * i / n, y0);
    l.paths.push_back(p);
    return l;
}

Eigen::Vector3d at(const Eigen::Vector2d& p, double z) {
    return {p.x(), p.y(), z};
}

std::vector<const ProgramEvent*> events_of(const PrintProgram& p, EventKind k) {
    std::vector<const ProgramEvent*> out;
    for (const auto& e : p.events)
        if (e.kind == k) out.push_back(&e);
    return out;
}

// Every event numbered 1..N in order; barriers only after a stop point.
void expect_well_numbered(const PrintProgram& p) {
    for (std::size_t i = 0; i < p.events.size(); ++i) {
        const ProgramEvent& e = p.events[i];
        EXPECT_EQ(e.sequence, static_cast<int>(i) + 1);
        ASSERT_LT(e.move, p.moves.size());
        if (i > 0) {
            EXPECT_GE(e.move, p.events[i - 1].move);
        }
        if (e.barrier) {
            EXPECT_EQ(e.anchor, EventAnchor::before);
            ASSERT_GT(e.move, 0u);
            EXPECT_TRUE(p.moves[e.move - 1].fine) << "barrier " << e.sequence;
        }
    }
}

}  // namespace

TEST(PrintProgram, SquareMovesAndEvents) {
    const RobotCellConfig cell;
    const PrintProgram p = build_print_program({square_layer(0, 0.8)}, cell, {});
    const RobotLayer square = square_layer(0, 0.8);
    const auto& pts = square.paths[0].points;
    // start (joint, above the first point), approach, 4 print moves (closing), final lift.
    ASSERT_EQ(p.moves.size(), 7u);
    const double safe = 0.8 + cell.motion.safe_height_mm;
    EXPECT_EQ(p.moves[0].role, MoveRole::start);
    EXPECT_TRUE(p.moves[0].joint);
    EXPECT_TRUE(p.moves[0].fine);
    EXPECT_NEAR((p.moves[0].position_mm - at(pts[0], safe)).norm(), 0, 1e-12);
    EXPECT_EQ(p.moves[1].role, MoveRole::approach);
    EXPECT_TRUE(p.moves[1].fine);
    EXPECT_EQ(p.moves[1].speed_mm_s, cell.motion.approach_speed_mm_s);
    EXPECT_NEAR((p.moves[1].position_mm - at(pts[0], 0.8)).norm(), 0, 1e-12);
    const int expect_point[] = {1, 2, 3, 0};
    for (int k = 0; k < 4; ++k) {
        const ProgramMove& m = p.moves[2 + k];
        EXPECT_EQ(m.role, MoveRole::print);
        EXPECT_EQ(m.nozzle, Nozzle::pla);
        EXPECT_EQ(m.point, expect_point[k]);
        EXPECT_EQ(m.layer, 0);
        EXPECT_EQ(m.path, 0);
        EXPECT_EQ(m.speed_mm_s, 12);
        EXPECT_NEAR((m.position_mm - at(pts[expect_point[k]], 0.8)).norm(), 0, 1e-12);
        EXPECT_NEAR(m.length_mm, 20, 1e-12);
        EXPECT_NEAR(signed_tilt_deg(m.orientation), 15, 1e-9);
        EXPECT_EQ(m.fine, k == 3);
        if (k < 3) {
            EXPECT_EQ(m.zone_mm, cell.motion.print_zone_mm);
        }
    }
    EXPECT_EQ(p.moves[6].role, MoveRole::lift);
    EXPECT_TRUE(p.moves[6].fine);  // a chunk may end here
    EXPECT_NEAR((p.moves[6].position_mm - at(pts[0], safe)).norm(), 0, 1e-12);

    // head_switch (select PLA) before the approach, extrude on/off, layer end on the lift.
    ASSERT_EQ(p.events.size(), 4u);
    expect_well_numbered(p);
    EXPECT_EQ(p.events[0].kind, EventKind::head_switch);
    EXPECT_TRUE(p.events[0].barrier);
    EXPECT_EQ(p.events[0].move, 1u);
    EXPECT_EQ(p.events[0].nozzle, Nozzle::pla);
    EXPECT_EQ(p.events[1].kind, EventKind::extrude_on);
    EXPECT_EQ(p.events[1].move, 2u);
    EXPECT_EQ(p.events[1].anchor, EventAnchor::start);
    EXPECT_TRUE(p.events[1].equipment_lag);
    EXPECT_NEAR(p.events[1].length_mm, 80, 1e-12);
    EXPECT_NEAR((p.events[1].position_mm - at(pts[0], 0.8)).norm(), 0, 1e-12);
    EXPECT_EQ(p.events[2].kind, EventKind::extrude_off);
    EXPECT_EQ(p.events[2].move, 5u);
    EXPECT_EQ(p.events[2].anchor, EventAnchor::end);
    EXPECT_EQ(p.events[3].kind, EventKind::layer_end);
    EXPECT_EQ(p.events[3].move, 6u);
    EXPECT_EQ(p.events[3].anchor, EventAnchor::start);
    EXPECT_EQ(p.events[3].layer, 0);

    EXPECT_EQ(p.stats.moves, 7u);
    EXPECT_EQ(p.stats.print_moves, 4u);
    EXPECT_EQ(p.stats.events, 4u);
    EXPECT_EQ(p.stats.barriers, 1u);
    EXPECT_EQ(p.stats.fine_points, 4u);
    EXPECT_NEAR(p.stats.print_length_mm, 80, 1e-9);
    // Duration by hand: print 80 mm at 12 mm/s, approach 5 mm at 20, lift 5 mm at 100, the
    // start move counts no length (it comes from anywhere), 4 stop points.
    const double expected = 80.0 / 12 + 5.0 / 20 + 5.0 / 100 + 4 * cell.motion.fine_allowance_s;
    EXPECT_NEAR(p.stats.duration_s, expected, 1e-9);
}

TEST(PrintProgram, FibrePathCutsTheCutterDistanceBeforeItsEnd) {
    const RobotCellConfig cell;
    // 100 mm, points every 10 mm: the cut at 58 mm falls inside the segment 50..60.
    const RobotLayer l = fibre_layer(0, 0.85);
    const PrintProgram p = build_print_program({l}, cell, {.cutter_distance_mm = 42});
    expect_well_numbered(p);
    const auto cuts = events_of(p, EventKind::cut);
    ASSERT_EQ(cuts.size(), 1u);
    const ProgramEvent& cut = *cuts[0];
    EXPECT_NEAR((cut.position_mm - Eigen::Vector3d(158, 150, 0.85)).norm(), 0, 1e-9);
    EXPECT_TRUE(cut.equipment_lag);
    EXPECT_NEAR(cut.length_mm, 42, 1e-12);
    // It is the end of a print move of its own (the segment was split there).
    const ProgramMove& m = p.moves[cut.move];
    EXPECT_EQ(m.role, MoveRole::print);
    EXPECT_EQ(m.point, -1);
    EXPECT_EQ(cut.anchor, EventAnchor::end);
    EXPECT_NEAR((m.position_mm - cut.position_mm).norm(), 0, 1e-12);
    // Arc length along the print moves from the cut to the path end.
    double rest = 0;
    for (std::size_t i = cut.move + 1; i < p.moves.size() && p.moves[i].role == MoveRole::print;
         ++i)
        rest += (p.moves[i].position_mm - p.moves[i - 1].position_mm).norm();
    EXPECT_NEAR(rest, 42, 0.01);

    const auto starts = events_of(p, EventKind::fibre_start);
    ASSERT_EQ(starts.size(), 1u);
    EXPECT_TRUE(starts[0]->barrier);
    EXPECT_EQ(p.moves[starts[0]->move - 1].role, MoveRole::approach);
    EXPECT_EQ(p.moves[starts[0]->move].role, MoveRole::print);
    EXPECT_NEAR(starts[0]->length_mm, 58, 1e-9);
    EXPECT_EQ(starts[0]->speed_mm_s, 5);
    const auto ends = events_of(p, EventKind::path_end);
    ASSERT_EQ(ends.size(), 1u);
    EXPECT_NEAR((ends[0]->position_mm - Eigen::Vector3d(200, 150, 0.85)).norm(), 0, 1e-12);
    EXPECT_GT(ends[0]->sequence, cut.sequence);
    EXPECT_TRUE(p.moves[ends[0]->move].fine);
    for (const auto& mv : p.moves) {
        EXPECT_EQ(mv.nozzle, Nozzle::ccf);
        EXPECT_NEAR(signed_tilt_deg(mv.orientation), -15, 1e-9);
        if (mv.role == MoveRole::print) {
            EXPECT_EQ(mv.speed_mm_s, 5);
        }
    }
}

TEST(PrintProgram, CutOnAnExistingPointAndOnAClosedFibrePath) {
    const RobotCellConfig cell;
    // Points every 2 mm: 58 mm is a point; no extra point is inserted.
    {
        const RobotLayer l = fibre_layer(0, 0.85, 100, 2);
        RobotCellConfig c = cell;
        c.motion.min_segment_mm = 0;
        c.motion.chord_tolerance_mm = 0;  // keep every point
        const PrintProgram p = build_print_program({l}, c, {});
        const auto cuts = events_of(p, EventKind::cut);
        ASSERT_EQ(cuts.size(), 1u);
        EXPECT_EQ(p.moves[cuts[0]->move].point, 29);
        EXPECT_NEAR(cuts[0]->position_mm.x(), 158, 1e-9);
    }
    // A closed 30 x 30 mm fibre ring: 120 mm around, ends where it started; the cut is 42 mm
    // before that, 78 mm along: (130, 130) -> (160, 130) -> (160, 160) -> (142, 160).
    {
        RobotLayer l{.index = 3, .z = 2.45, .nozzle = Nozzle::ccf};
        l.paths.push_back(
            {true, {{130, 130}, {160, 130}, {160, 160}, {130, 160}}});
        const PrintProgram p = build_print_program({l}, cell, {});
        const auto cuts = events_of(p, EventKind::cut);
        ASSERT_EQ(cuts.size(), 1u);
        EXPECT_NEAR((cuts[0]->position_mm - Eigen::Vector3d(142, 160, 2.45)).norm(), 0, 1e-9);
        const auto ends = events_of(p, EventKind::path_end);
        EXPECT_NEAR((ends[0]->position_mm - Eigen::Vector3d(130, 130, 2.45)).norm(), 0, 1e-12);
        EXPECT_EQ(p.moves[ends[0]->move].point, 0);
        EXPECT_EQ(cuts[0]->layer, 3);
    }
}

TEST(PrintProgram, HeadSwitchBetweenPlaAndCcfLayers) {
    const RobotCellConfig cell;
    const std::vector<RobotLayer> layers = {square_layer(0, 0.8), fibre_layer(1, 0.85)};
    const PrintProgram p = build_print_program(layers, cell, {});
    expect_well_numbered(p);

    // The PLA path's end, then: lift (PLA, stop), turn (CCF, stop), barrier, travel, approach.
    std::size_t off = p.events[2].move;
    ASSERT_EQ(p.events[2].kind, EventKind::extrude_off);
    const ProgramMove& lift = p.moves[off + 1];
    const ProgramMove& turn = p.moves[off + 2];
    const ProgramMove& travel = p.moves[off + 3];
    const ProgramMove& approach = p.moves[off + 4];
    EXPECT_EQ(lift.role, MoveRole::lift);
    EXPECT_EQ(lift.nozzle, Nozzle::pla);
    EXPECT_TRUE(lift.fine);
    // 20 mm (head-switch height) above the part top or the next layer, whichever is higher
    // (0.85 mm), straight above the path end (140, 140).
    EXPECT_NEAR((lift.position_mm - Eigen::Vector3d(140, 140, 20.85)).norm(), 0, 1e-12);
    EXPECT_EQ(turn.role, MoveRole::turn);
    EXPECT_EQ(turn.nozzle, Nozzle::ccf);
    EXPECT_TRUE(turn.fine);
    EXPECT_NEAR(signed_tilt_deg(turn.orientation), -15, 1e-9);
    // The flange stays put: the CCF tip lands where the flange puts it, computed by hand.
    {
        Eigen::Isometry3d pla_tcp = Eigen::Isometry3d::Identity();
        pla_tcp.linear() = lift.orientation.toRotationMatrix();
        pla_tcp.translation() = lift.position_mm;
        const Eigen::Isometry3d flange = pla_tcp * cell.head.pla.tframe.inverse();
        Eigen::Isometry3d flange_after = flange;
        flange_after.linear() =
            turn.orientation.toRotationMatrix() * cell.head.ccf.tframe.linear().transpose();
        const Eigen::Vector3d ccf_tip = flange_after * cell.head.ccf.tframe.translation();
        EXPECT_NEAR((turn.position_mm - ccf_tip).norm(), 0, 1e-9);
        // With the mirror-symmetric head the CCF tip turns to the PLA tip's height, mirrored
        // across the vertical plane through the tilt axis (0.44 mm to either side of it).
        EXPECT_NEAR(turn.position_mm.z(), lift.position_mm.z(), 1e-9);
        EXPECT_NEAR(turn.position_mm.x(), lift.position_mm.x(), 1e-9);
        EXPECT_LT((turn.position_mm - lift.position_mm).norm(), 1.0);
        // The pure tilt: 30 deg between the two orientations, about the tilt axis.
        EXPECT_NEAR(lift.orientation.angularDistance(turn.orientation) * 180 / pi, 30, 1e-9);
    }
    const ProgramEvent& sw = p.events[4];
    EXPECT_EQ(p.events[3].kind, EventKind::layer_end);
    EXPECT_EQ(p.events[3].move, off + 1);  // at the start of the lift
    EXPECT_EQ(sw.kind, EventKind::head_switch);
    EXPECT_TRUE(sw.barrier);
    EXPECT_EQ(sw.nozzle, Nozzle::ccf);
    EXPECT_EQ(sw.move, off + 3);  // before the travel, after the turn
    EXPECT_EQ(travel.role, MoveRole::travel);
    EXPECT_NEAR((travel.position_mm - Eigen::Vector3d(100, 150, 0.85 + 5)).norm(), 0, 1e-12);
    EXPECT_EQ(approach.role, MoveRole::approach);
    EXPECT_EQ(p.events[5].kind, EventKind::fibre_start);
    EXPECT_EQ(p.events[5].move, off + 5);
    EXPECT_EQ(p.stats.head_switches, 1u);
    EXPECT_EQ(p.stats.layers, 2u);
    EXPECT_EQ(p.stats.barriers, 3u);  // first head select, head switch, fibre thread
    // The last two events: path end, layer end (at the final lift).
    EXPECT_EQ(p.events.back().kind, EventKind::layer_end);
    EXPECT_EQ(p.events.back().layer, 1);
    EXPECT_EQ(p.moves.back().role, MoveRole::lift);
    EXPECT_TRUE(p.moves.back().fine);
}

TEST(PrintProgram, TravelStaysAboveThePartsCurrentTop) {
    const RobotCellConfig cell;
    // Two PLA paths on layer 0, then layer 1 higher up.
    RobotLayer l0 = square_layer(0, 0.8);
    l0.paths.push_back(square_layer(0, 0.8, 180, 140).paths[0]);
    const PrintProgram p = build_print_program({l0, square_layer(1, 1.6)}, cell, {});
    double top = 0;
    for (const ProgramMove& m : p.moves) {
        if (m.role == MoveRole::print) top = std::max(top, m.position_mm.z());
        if (m.role == MoveRole::lift || m.role == MoveRole::travel) {
            EXPECT_GE(m.position_mm.z(), top + cell.motion.safe_height_mm - 1e-9);
        }
    }
    EXPECT_EQ(events_of(p, EventKind::layer_end).size(), 2u);
    EXPECT_EQ(events_of(p, EventKind::extrude_on).size(), 3u);
    EXPECT_EQ(events_of(p, EventKind::head_switch).size(), 1u);  // only the first selection
}

TEST(PrintProgram, IdleNozzleClearanceViolationIsReported) {
    RobotCellConfig cell;
    // Nozzles 4 mm apart: the tilt lifts the idle one by 4 sin 15 = 1.04 mm < 3 mm.
    cell.head.pla.tframe = HeadConfig::default_tframe(-2);
    cell.head.ccf.tframe = HeadConfig::default_tframe(2);
    try {
        build_print_program({square_layer(0, 0.8)}, cell, {});
        FAIL() << "expected a clearance violation";
    } catch (const PrintProgramError& e) {
        ASSERT_FALSE(e.issues().empty());
        const ProgramIssue& i = e.issues().front();
        EXPECT_EQ(i.layer, 0);
        EXPECT_EQ(i.path, 0);
        EXPECT_EQ(i.point, 0);
        EXPECT_NE(i.message.find("idle ccf nozzle"), std::string::npos) << i.message;
        EXPECT_NE(std::string(e.what()).find("layer 1 path 1 point 1"), std::string::npos);
    }
}

TEST(PrintProgram, ClearanceIsAgainstTheHighestPrintedZ) {
    const RobotCellConfig cell;  // idle lift 12.94 mm, clearance 3 mm
    // A layer at 20 mm, then one at 5 mm: the idle tip (17.94 mm) is under 20 + 3 mm.
    try {
        build_print_program({square_layer(0, 20), square_layer(1, 5)}, cell, {});
        FAIL() << "expected a clearance violation";
    } catch (const PrintProgramError& e) {
        EXPECT_EQ(e.issues().front().layer, 1);
        EXPECT_NE(e.issues().front().message.find("part top 20.000 mm"), std::string::npos)
            << e.issues().front().message;
    }
    // At 12 mm the idle tip is at 24.94 mm: clear.
    EXPECT_NO_THROW(build_print_program({square_layer(0, 20), square_layer(1, 12)}, cell, {}));
}

TEST(PrintProgram, ShortFibrePathIsAnError) {
    const RobotCellConfig cell;
    try {
        build_print_program({fibre_layer(2, 0.85, 30, 5)}, cell, {.cutter_distance_mm = 42});
        FAIL();
    } catch (const PrintProgramError& e) {
        EXPECT_EQ(e.issues().front().layer, 2);
        EXPECT_EQ(e.issues().front().path, 0);
        EXPECT_NE(e.issues().front().message.find("shorter than the cutter distance"),
                  std::string::npos);
    }
}

TEST(PrintProgram, DegeneratePathsAreSkippedWithAWarning) {
    const RobotCellConfig cell;
    RobotLayer l = square_layer(0, 0.8);
    l.paths.insert(l.paths.begin(), RobotPath{false, {{10, 10}, {10, 10}}});
    const PrintProgram p = build_print_program({l}, cell, {});
    ASSERT_EQ(p.warnings.size(), 1u);
    EXPECT_NE(p.warnings[0].find("layer 1 path 1"), std::string::npos);
    EXPECT_EQ(p.stats.paths, 1u);
    for (const ProgramMove& m : p.moves)
        if (m.role == MoveRole::print) {
            EXPECT_EQ(m.path, 1);
        }
}

TEST(PointMerge, KeepsThePathWithinTheChordToleranceAndEveryFixedPoint) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(-0.008, 0.008);
    // A wavy line: long straight stretches with noise, then a bend every 100 points.
    std::vector<Eigen::Vector2d> pts;
    double x = 0, y = 0, heading = 0;
    for (int i = 0; i < 1000; ++i) {
        if (i % 100 == 0) heading += 0.4;
        x += 0.1 * std::cos(heading);
        y += 0.1 * std::sin(heading);
        pts.emplace_back(x + noise(rng), y + noise(rng));
    }
    const std::vector<std::size_t> fixed = {17, 333, 334, 750};
    const PointMergeOptions o{.chord_tolerance_mm = 0.02, .min_segment_mm = 0};
    const std::vector<std::size_t> kept = merge_points(pts, fixed, o);
    EXPECT_LT(kept.size(), 200u);  // most points go
    EXPECT_EQ(kept.front(), 0u);
    EXPECT_EQ(kept.back(), pts.size() - 1);
    for (const std::size_t f : fixed) {
        EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), f)) << f;
    }
    // Every dropped point lies within the tolerance of the segment that replaced it.
    for (std::size_t k = 1; k < kept.size(); ++k) {
        ASSERT_LT(kept[k - 1], kept[k]);
        for (std::size_t i = kept[k - 1] + 1; i < kept[k]; ++i) {
            const Eigen::Vector2d a = pts[kept[k - 1]], b = pts[kept[k]];
            const double t = std::clamp((pts[i] - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
            EXPECT_LE((pts[i] - (a + t * (b - a))).norm(), 0.02 + 1e-12) << i;
        }
    }
}

TEST(PointMerge, EnforcesTheMinimumSegmentExceptAtFixedPoints) {
    // A circle of radius 10 mm sampled every 0.05 mm: the chord tolerance alone keeps short
    // segments; the minimum length drops them.
    std::vector<Eigen::Vector2d> pts;
    const int n = static_cast<int>(2 * pi * 10 / 0.05);
    for (int i = 0; i <= n; ++i)
        pts.emplace_back(10 * std::cos(2 * pi * i / n), 10 * std::sin(2 * pi * i / n));
    const std::vector<std::size_t> fixed = {400, 402};
    const PointMergeOptions o{.chord_tolerance_mm = 0.0001, .min_segment_mm = 0.5};
    const std::vector<std::size_t> kept = merge_points(pts, fixed, o);
    for (std::size_t k = 1; k < kept.size(); ++k) {
        const bool touches_fixed = std::binary_search(fixed.begin(), fixed.end(), kept[k]) ||
                                   std::binary_search(fixed.begin(), fixed.end(), kept[k - 1]) ||
                                   k + 1 == kept.size();
        if (!touches_fixed) {
            EXPECT_GE((pts[kept[k]] - pts[kept[k - 1]]).norm(), 0.5 - 1e-9) << k;
        }
    }
    EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), 400u));
    EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), 402u));
}

TEST(PrintProgram, MergingKeepsEveryEventPoint) {
    RobotCellConfig cell;
    cell.motion.chord_tolerance_mm = 0.05;
    cell.motion.min_segment_mm = 0.3;
    // A 100 mm fibre path sampled every 0.01 mm with noise under the tolerance.
    RobotLayer l{.index = 0, .z = 0.85, .nozzle = Nozzle::ccf};
    RobotPath path{false, {}};
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(-0.01, 0.01);
    for (int i = 0; i <= 10000; ++i) path.points.emplace_back(100 + i * 0.01, 150 + noise(rng));
    l.paths.push_back(path);
    const PrintProgram p = build_print_program({l}, cell, {});
    EXPECT_GT(p.stats.points_merged, 9900u);
    EXPECT_LT(p.stats.print_moves, 20u);
    // The cut stays exactly 42 mm of toolpath (noise included) before the end, walked back here.
    double rest = 42;
    Eigen::Vector2d expected_cut = path.points.front();
    for (std::size_t i = path.points.size() - 1; i > 0; --i) {
        const double seg = (path.points[i] - path.points[i - 1]).norm();
        if (seg >= rest) {
            expected_cut = path.points[i] + (rest / seg) * (path.points[i - 1] - path.points[i]);
            break;
        }
        rest -= seg;
    }
    const auto cut = events_of(p, EventKind::cut);
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_NEAR((cut[0]->position_mm - at(expected_cut, 0.85)).norm(), 0, 1e-6);
    EXPECT_GT(cut[0]->position_mm.x(), 158);  // the noise makes the path longer than 100 mm
    EXPECT_NEAR(
        (events_of(p, EventKind::path_end)[0]->position_mm - at(path.points.back(), 0.85)).norm(),
        0, 1e-12);
    for (const ProgramMove& m : p.moves)
        if (m.role == MoveRole::print && m.point >= 0) {
            EXPECT_NEAR((m.position_mm - at(path.points[m.point], 0.85)).norm(), 0, 1e-12);
        }
    // Every toolpath point stays within the tolerance of the printed polyline.
    std::vector<Eigen::Vector2d> printed;
    for (const ProgramMove& m : p.moves)
        if (m.role == MoveRole::print || m.role == MoveRole::approach)
            printed.push_back(m.position_mm.head<2>());
    for (const auto& q : path.points) {
        double best = 1e9;
        for (std::size_t k = 1; k < printed.size(); ++k)
            best = std::min(best, distance_to_segment(q, printed[k - 1], printed[k]));
        EXPECT_LE(best, 0.05 + 1e-9);
    }
}

TEST(PrintProgram, NoZeroLengthMoves) {
    const RobotCellConfig cell;
    // Two rings starting at the same point: after the lift the head is already above the start.
    RobotLayer l = square_layer(0, 0.8);
    l.paths.push_back(square_layer(0, 0.8, 140, 140, 10).paths[0]);
    const PrintProgram p = build_print_program({l}, cell, {});
    for (std::size_t i = 1; i < p.moves.size(); ++i) {
        EXPECT_GT((p.moves[i].position_mm - p.moves[i - 1].position_mm).norm(), 1e-6) << i;
    }
    // square, lift, approach, square, lift.
    EXPECT_EQ(p.stats.travel_moves, 1u + 1 + 1 + 1 + 1);
}
