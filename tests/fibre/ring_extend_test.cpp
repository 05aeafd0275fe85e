// Boundary arcs too short to cut run on along their 1.5W loop (Section 4.4, a small selected
// patch of the outline): measured on the points, against the loop they must stay on.

#include "planner/fibre/ring_extend.hpp"

#include "planner/fibre/segment_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace fibrecell::planner {
namespace {

// A square's outline, counter-clockwise from `at`, a vertex every 1 mm.
Polygon square(double side, Eigen::Vector2d at = {0, 0}) {
    Polygon loop;
    const Eigen::Vector2d corners[4] = {at, at + Eigen::Vector2d(side, 0),
                                        at + Eigen::Vector2d(side, side),
                                        at + Eigen::Vector2d(0, side)};
    for (int c = 0; c < 4; ++c)
        for (int i = 0; i < static_cast<int>(side); ++i)
            loop.push_back(corners[c] + (corners[(c + 1) % 4] - corners[c]) * (i / side));
    return loop;
}

// The arc of `loop` from vertex `from` to vertex `to` (inclusive), in the loop's order.
Polyline arc(const Polygon& loop, int from, int to) {
    Polyline out;
    for (int k = from; k <= to; ++k) out.points.push_back(loop[static_cast<std::size_t>(k)]);
    return out;
}

double distance_to_loop(const Polygon& loop, const Eigen::Vector2d& p) {
    double best = HUGE_VAL;
    for (std::size_t k = 0; k < loop.size(); ++k)
        best = std::min(best, point_segment_distance(p, loop[k], loop[(k + 1) % loop.size()]));
    return best;
}

TEST(RingExtend, AShortArcGrowsBothWaysAlongItsLoopToTheCutterDistance) {
    const Polygon loop = square(20);                // 80 mm round
    std::vector<Polyline> rings{arc(loop, 5, 15)};  // 10 mm along the bottom
    const Polyline before = rings[0];
    EXPECT_EQ(extend_short_rings(rings, {loop}, {.min_length_mm = 42, .step_mm = 1}), 1u);
    const Polyline& r = rings[0];
    EXPECT_FALSE(r.closed);
    const double length = polyline_length(r);
    EXPECT_GE(length, 42.0);
    EXPECT_LT(length, 43.0);
    for (std::size_t k = 0; k < r.points.size(); ++k) {
        EXPECT_LT(distance_to_loop(loop, r.points[k]), 1e-9) << r.points[k].transpose();
        if (k > 0) {
            EXPECT_LE((r.points[k] - r.points[k - 1]).norm(), 1.0 + 1e-9);
        }
    }
    // The arc it was, in place and in order, with about as much added before as after it.
    const auto first = std::find(r.points.begin(), r.points.end(), before.points.front());
    ASSERT_NE(first, r.points.end());
    ASSERT_LE(static_cast<std::size_t>(r.points.end() - first), r.points.size());
    for (std::size_t k = 0; k < before.points.size(); ++k)
        EXPECT_EQ(*(first + static_cast<std::ptrdiff_t>(k)), before.points[k]);
    const double ahead = polyline_length(
        {{first + static_cast<std::ptrdiff_t>(before.points.size()) - 1, r.points.end()}});
    const double behind = polyline_length({{r.points.begin(), first + 1}});
    EXPECT_NEAR(ahead, behind, 1.0);
    EXPECT_NEAR(ahead + behind, 32.0, 1.0);
}

TEST(RingExtend, ArcsLongEnoughClosedRingsAndLoopsTooShortStayAsTheyAre) {
    const Polygon big = square(20), small = square(10, {50, 0});  // 80 and 40 mm round
    std::vector<Polyline> rings{arc(big, 0, 50), arc(small, 2, 8), Polyline{small, true, 0}};
    const std::vector<Polyline> before = rings;
    EXPECT_EQ(extend_short_rings(rings, {big, small}, {.min_length_mm = 42, .step_mm = 1}), 0u);
    for (std::size_t i = 0; i < rings.size(); ++i) EXPECT_EQ(rings[i].points, before[i].points);
}

}  // namespace
}  // namespace fibrecell::planner
