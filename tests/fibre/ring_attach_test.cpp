// Rings shorter than the cutter distance laid on from a stress path (Section 4.4): a pin hole's
// ring opened where the link meets it, and left alone when no path can reach it keeping W.

#include "planner/fibre/ring_attach.hpp"

#include "../toolpaths/toolpath_test_shapes.hpp"
#include "spacing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace fibrecell::planner {
namespace {

using ::fibrecell::test::W;
const Eigen::Vector2d pin(20, 15);

// The ring 1.5W round a pin hole of radius 5, points 0.5 mm apart: 40.8 mm, under 42.
Polyline pin_ring(double radius = 6.5) {
    Polyline ring{.points = {}, .closed = true};
    const int n = static_cast<int>(std::ceil(2 * std::numbers::pi * radius / 0.5));
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        ring.points.push_back(pin + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return ring;
}

Polyline line(Eigen::Vector2d a, Eigen::Vector2d b) {
    return {{a, b}, false, 0};
}

// A ring along part of a selected edge: the arc y = 2, x = 5..25 (20 mm), points 0.5 mm apart.
Polyline edge_arc() {
    Polyline arc{.points = {}, .closed = false};
    for (double x = 5; x <= 25 + 1e-9; x += 0.5) arc.points.push_back({x, 2});
    return arc;
}

std::vector<Polygon> plate() {
    return {test::rectangle(0.5, 0.5, 39.5, 29.5), test::circle_hole(pin, 5.5, 64)};
}

// Smallest distance between points of one polyline more than 4W apart along it, brute force on
// points every W/10.
double self_spacing(const std::vector<Eigen::Vector2d>& pts) {
    std::vector<Eigen::Vector2d> p;
    std::vector<double> along;
    double s = 0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const double l = (pts[i + 1] - pts[i]).norm();
        const int n = std::max(1, static_cast<int>(std::ceil(l / (W / 10))));
        for (int k = 0; k < n; ++k) {
            p.push_back(pts[i] + (pts[i + 1] - pts[i]) * (double(k) / n));
            along.push_back(s + l * k / n);
        }
        s += l;
    }
    double best = 1e9;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j)
            if (along[j] - along[i] > 4 * W) best = std::min(best, (p[i] - p[j]).norm());
    return best;
}

TEST(RingAttach, APinRingShorterThanTheCutterIsLaidOnFromTheNearestPath) {
    // A path coming up to 2.5W below the pin hole, where the stress fibres are cut.
    std::vector<Polyline> paths = {line({20, 1}, {20, 7.5})};
    std::vector<Polyline> rings = {pin_ring()};
    const double ring_length = 2 * 6.5 * std::sin(std::numbers::pi / 82) * 82;
    EXPECT_EQ(
        attach_short_rings(paths, rings, plate(), {.spacing_mm = W, .cutter_distance_mm = 42}), 1u);
    EXPECT_TRUE(rings.empty());
    ASSERT_EQ(paths.size(), 1u);
    const auto& p = paths[0].points;
    double length = 0;
    for (std::size_t i = 1; i < p.size(); ++i) length += (p[i] - p[i - 1]).norm();
    // The run, the 1 mm link, the ring less the 1.5W it stops short of coming round.
    EXPECT_NEAR(length, 6.5 + 1.0 + ring_length - 1.5 * W, 0.5);
    EXPECT_GE(length, 42);  // now long enough to cut
    EXPECT_GE(self_spacing(p), W);
    int on_ring = 0;
    for (const auto& q : p) on_ring += std::abs((q - pin).norm() - 6.5) < 1e-9;
    EXPECT_GT(on_ring, 70);
}

TEST(RingAttach, ARingNoPathReachesIsLeft) {
    std::vector<Polyline> paths = {line({20, 1}, {20, 4})};  // ends 4.5 mm below the ring
    std::vector<Polyline> rings = {pin_ring()};
    EXPECT_EQ(attach_short_rings(paths, rings, plate(), {.spacing_mm = W}), 0u);
    EXPECT_EQ(rings.size(), 1u);
    EXPECT_EQ(paths[0].points.size(), 2u);
}

TEST(RingAttach, ALinkThatWouldPassCloserThanWToAnotherPathIsNotMade) {
    // A second path crosses between the end and the ring.
    std::vector<Polyline> paths = {line({20, 1}, {20, 6.5}), line({10, 7.5}, {30, 7.5})};
    std::vector<Polyline> rings = {pin_ring()};
    EXPECT_EQ(attach_short_rings(paths, rings, plate(), {.spacing_mm = W, .reach_mm = 3}), 0u);
    EXPECT_EQ(rings.size(), 1u);
}

TEST(RingAttach, RingsLongEnoughToCutStayRings) {
    std::vector<Polyline> paths = {line({20, 1}, {20, 6.5})};
    std::vector<Polyline> rings = {pin_ring(8.0)};  // 50 mm
    EXPECT_EQ(
        attach_short_rings(paths, rings, plate(), {.spacing_mm = W, .cutter_distance_mm = 42}), 0u);
    EXPECT_EQ(rings.size(), 1u);
}

TEST(RingAttach, AnArcIsLaidFromItsNearerEnd) {
    // The edge arc and a path of 25 mm ending 1 mm above its right end.
    std::vector<Polyline> paths = {line({25, 28}, {25, 3})};
    std::vector<Polyline> rings = {edge_arc()};
    EXPECT_EQ(attach_short_rings(paths, rings, plate(), {.spacing_mm = W}), 1u);
    const auto& p = paths[0].points;
    EXPECT_EQ(p.back(), Eigen::Vector2d(5, 2));
    EXPECT_EQ(p[2], Eigen::Vector2d(25, 2));
}

TEST(RingAttach, AJoinStillTooShortToCutIsNotMade) {
    // The same arc and a path of 17 mm: joined, 38 mm, under the 42 mm cutter distance, and the
    // whole would be dropped. The ring is left (to run on along its edge: ring_extend).
    std::vector<Polyline> paths = {line({25, 20}, {25, 3})};
    std::vector<Polyline> rings = {edge_arc()};
    EXPECT_EQ(attach_short_rings(paths, rings, plate(), {.spacing_mm = W}), 0u);
    EXPECT_EQ(rings.size(), 1u);
    EXPECT_EQ(paths[0].points.size(), 2u);
}

}  // namespace
}  // namespace fibrecell::planner
