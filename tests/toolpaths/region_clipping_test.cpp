// The region operations the fibre planner clips with: offsets (and how far their round joins
// cut in), bands round outline segments, differences, and open polylines clipped to a region,
// checked against distances and crossings worked out here by hand.

#include "planner/toolpaths/polygon_offset.hpp"

#include "toolpath_test_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fibrecell::planner {
namespace {

using test::circle_hole;
using test::rectangle;
using test::segment_distance;

double run_length(const std::vector<Eigen::Vector2d>& run) {
    double l = 0;
    for (std::size_t i = 1; i < run.size(); ++i) l += (run[i] - run[i - 1]).norm();
    return l;
}

// Every edge point of the region, sampled every 0.05 mm.
template <class F>
void each_edge_point(const std::vector<Polygon>& region, F f) {
    for (const Polygon& loop : region)
        for (std::size_t i = 0; i < loop.size(); ++i) {
            const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % loop.size()];
            const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.05)));
            for (int k = 0; k < n; ++k) f(a + (b - a) * (double(k) / n));
        }
}

TEST(RegionClipping, InsetChordsCutInNoMoreThanTheDocumentedBound) {
    // A hole's inset grows it with round joins at every vertex; a 17-gon gives short arcs whose
    // chord count Clipper rounds down.
    const LayerOutline outline{{rectangle(0, 0, 40, 40), circle_hole({20, 20}, 6, 17)}};
    const OffsetOptions options{.arc_tolerance_mm = 0.002};
    const auto inset = offset_region(outline.loops, -0.5, options);
    double nearest = 1e9;
    each_edge_point(inset, [&](const Eigen::Vector2d& p) {
        nearest = std::min(nearest, test::distance_to_outline(p, outline));
    });
    EXPECT_GE(nearest, 0.5 - 2.25 * options.arc_tolerance_mm - 1e-5);
    EXPECT_LE(nearest, 0.5);
}

TEST(RegionClipping, SegmentBandIsTheUnionOfCapsules) {
    const std::vector<Segment2> segments = {{{{0, 0}, {10, 0}}}, {{{10, 0}, {10, 10}}}};
    const auto band = segment_band(segments, 2.0);
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(5, 1.9), Eigen::Vector2d(-1.9, 0),
                                     Eigen::Vector2d(11.9, 5), Eigen::Vector2d(11.3, -1.3)})
        EXPECT_TRUE(inside_region(band, p)) << p.transpose();
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(5, 2.1), Eigen::Vector2d(-2.1, 0),
                                     Eigen::Vector2d(5, 5), Eigen::Vector2d(10, 12.1)})
        EXPECT_FALSE(inside_region(band, p)) << p.transpose();
    EXPECT_TRUE(segment_band({}, 2.0).empty());
    EXPECT_THROW(segment_band(segments, 0.0), std::invalid_argument);
}

TEST(RegionClipping, DifferenceCutsTheBandOut) {
    const std::vector<Polygon> plate = {rectangle(0, 0, 20, 10)};
    const auto cut = region_difference(plate, segment_band({{{{0, 0}, {20, 0}}}}, 3.0));
    EXPECT_FALSE(inside_region(cut, {10, 2.9}));
    EXPECT_TRUE(inside_region(cut, {10, 3.1}));
    EXPECT_TRUE(inside_region(cut, {10, 9.9}));
    EXPECT_EQ(region_difference(plate, {}).size(), 1u);
}

TEST(RegionClipping, OpenLineAcrossAHoleComesBackAsTwoRunsInItsOrder) {
    const std::vector<Polygon> region = {rectangle(0, 0, 30, 20), rectangle(10, 5, 20, 15)};
    // Right to left through the hole, so the runs must keep that direction and order.
    const ClippedRuns r = clip_polyline(region, {{35, 10}, {-5, 10}}, false);
    ASSERT_EQ(r.runs.size(), 2u);
    EXPECT_FALSE(r.closed_inside);
    EXPECT_NEAR(r.runs[0].front().x(), 30, 1e-5);
    EXPECT_NEAR(r.runs[0].back().x(), 20, 1e-5);
    EXPECT_NEAR(r.runs[1].front().x(), 10, 1e-5);
    EXPECT_NEAR(r.runs[1].back().x(), 0, 1e-5);
    EXPECT_NEAR(run_length(r.runs[0]) + run_length(r.runs[1]), 20, 1e-4);
}

TEST(RegionClipping, ClosedLineKeepsItsRunThroughTheStart) {
    const std::vector<Polygon> region = {rectangle(0, 0, 10, 10)};
    // A square loop half outside: one run, from the right edge round the inside and back.
    const ClippedRuns half = clip_polyline(region, {{5, 2}, {15, 2}, {15, 8}, {5, 8}}, true);
    ASSERT_EQ(half.runs.size(), 1u);
    EXPECT_FALSE(half.closed_inside);
    EXPECT_NEAR(run_length(half.runs[0]), 5 + 6 + 5, 1e-4);
    const ClippedRuns whole = clip_polyline(region, {{2, 2}, {8, 2}, {8, 8}, {2, 8}}, true);
    ASSERT_EQ(whole.runs.size(), 1u);
    EXPECT_TRUE(whole.closed_inside);
    EXPECT_TRUE(clip_polyline(region, {{20, 20}, {30, 30}}, false).runs.empty());
}

// Many lines against one region: lines clear of the outline come back whole or not at all
// without Clipper, and every line's runs are clip_polyline's, to its rounding.
TEST(RegionClipping, ARegionClipGivesClipPolylinesRunsForEveryLine) {
    const std::vector<Polygon> region = {rectangle(0, 0, 30, 20), circle_hole({15, 10}, 4, 64)};
    const RegionClip clip(region);
    const std::vector<std::pair<std::vector<Eigen::Vector2d>, bool>> lines = {
        {{{2, 2}, {8, 3}, {12, 2}}, false},                 // inside, clear of every edge
        {{{2, 2}, {8, 2}, {8, 5}, {2, 5}}, true},           // a closed loop inside
        {{{40, 2}, {50, 3}}, false},                        // outside
        {{{13, 10}, {17, 10}}, false},                      // in the hole
        {{{-5, 10}, {35, 10}}, false},                      // across the part and its hole
        {{{5, 1}, {35, 1}, {35, 3}, {5, 3}}, true},         // a loop across the right edge
        {{{0, 5}, {10, 5}}, false},                         // from a point on the outline
        {{{5, 0}, {25, 0}}, false},                         // along an edge
        {{{2, 2}, {30 - 1e-7, 2}, {2, 3}}, false},          // touching the edge within 1e-7
    };
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const auto& [line, closed] = lines[i];
        const ClippedRuns want = clip_polyline(region, line, closed);
        const ClippedRuns got = clip(line, closed);
        ASSERT_EQ(got.runs.size(), want.runs.size()) << "line " << i;
        EXPECT_EQ(got.closed_inside, want.closed_inside) << "line " << i;
        for (std::size_t r = 0; r < want.runs.size(); ++r) {
            ASSERT_EQ(got.runs[r].size(), want.runs[r].size()) << "line " << i << " run " << r;
            for (std::size_t k = 0; k < want.runs[r].size(); ++k)
                EXPECT_LT((got.runs[r][k] - want.runs[r][k]).norm(), 1e-5)
                    << "line " << i << " run " << r << " point " << k;
        }
    }
    // Segments: a chord across the hole is not inside, one beside it is, a point always is.
    EXPECT_FALSE(clip.holds_segment({5, 10}, {25, 10}));
    EXPECT_TRUE(clip.holds_segment({5, 2}, {25, 2}));
    EXPECT_FALSE(clip.holds_segment({25, 2}, {35, 2}));
    EXPECT_TRUE(clip.holds_segment({25, 2}, {30, 2}));  // ends on the edge
    EXPECT_TRUE(clip.holds_segment({50, 50}, {50, 50}));
}

}  // namespace
}  // namespace fibrecell::planner
