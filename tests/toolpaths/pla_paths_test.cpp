// PLA matrix layers: perimeters at w/2 + i*w, zigzag infill at spacing w inside them, direction
// turned 45 degrees per layer, nearest-first order.

#include "planner/toolpaths/pla_paths.hpp"

#include "planner/toolpaths/path_order.hpp"
#include "toolpath_test_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

using test::distance_to_outline;
using test::inside;
using test::with_role;

constexpr double w = 0.8;
constexpr double ring_tolerance = 1e-3;   // ring vertices sit on the exact offset
constexpr double chord_tolerance = 3e-3;  // arc_tolerance_mm (0.002) + rounding

// Index i of the ring whose every vertex lies w/2 + i*w from the outline; -1 when none fits.
int ring_index(const Toolpath& ring, const LayerOutline& outline) {
    const double d0 = distance_to_outline(ring.points.front(), outline);
    const int i = static_cast<int>(std::lround((d0 - w / 2) / w));
    for (const Eigen::Vector2d& p : ring.points)
        if (std::abs(distance_to_outline(p, outline) - (w / 2 + i * w)) > ring_tolerance) return -1;
    return i;
}

// The invariant of the infill: every point of every infill segment (sampled) lies inside the
// outline and at least perimeters * w from it (the innermost perimeter's centreline is at
// (perimeters - 1/2) * w, and the infill centrelines stay another w/2 in), up to the chord
// error of round joins.
void expect_infill_inside(const std::vector<Toolpath>& infill, const LayerOutline& outline,
                          double min_distance) {
    for (const Toolpath& path : infill) {
        EXPECT_FALSE(path.closed);
        for (std::size_t i = 1; i < path.points.size(); ++i)
            for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
                const Eigen::Vector2d p = (1 - t) * path.points[i - 1] + t * path.points[i];
                ASSERT_TRUE(inside(p, outline)) << p.transpose();
                ASSERT_GE(distance_to_outline(p, outline), min_distance - chord_tolerance)
                    << p.transpose();
            }
    }
}

// Perpendicular positions of the scan segments (pieces along `angle_deg`) are w apart.
void expect_scan_spacing(const std::vector<Toolpath>& infill, double angle_deg) {
    const double a = angle_deg * std::numbers::pi / 180;
    const Eigen::Vector2d normal(-std::sin(a), std::cos(a));
    std::vector<double> offsets;
    for (const test::Piece& piece : test::long_pieces(infill, 1e-6)) {
        const double dir = test::direction_deg(piece);
        const double want = std::fmod(std::fmod(angle_deg, 180) + 180, 180);
        if (std::abs(dir - want) > 1e-6 && std::abs(std::abs(dir - want) - 180) > 1e-6) continue;
        offsets.push_back(normal.dot(piece.a));
    }
    ASSERT_GE(offsets.size(), 2u);
    std::sort(offsets.begin(), offsets.end());
    std::vector<double> lines{offsets.front()};
    for (double o : offsets)
        if (o - lines.back() > 1e-6) lines.push_back(o);
    for (std::size_t i = 1; i < lines.size(); ++i) EXPECT_NEAR(lines[i] - lines[i - 1], w, 1e-6);
}

void expect_rings_and_infill(const LayerOutline& outline, int loops_per_ring) {
    const std::vector<Toolpath> paths = pla_layer_paths(outline, 0);
    const std::vector<Toolpath> rings = with_role(paths, PathRole::perimeter);
    ASSERT_EQ(rings.size(), static_cast<std::size_t>(2 * loops_per_ring));
    std::multiset<int> indices;
    for (const Toolpath& ring : rings) {
        EXPECT_TRUE(ring.closed);
        indices.insert(ring_index(ring, outline));
    }
    EXPECT_EQ(indices.count(0), static_cast<std::size_t>(loops_per_ring));
    EXPECT_EQ(indices.count(1), static_cast<std::size_t>(loops_per_ring));
    const std::vector<Toolpath> infill = with_role(paths, PathRole::infill);
    ASSERT_FALSE(infill.empty());
    expect_infill_inside(infill, outline, 2 * w);
}

TEST(PlaPaths, RectanglePerimetersAtHalfWidthPlusPitch) {
    expect_rings_and_infill(test::rectangle_outline(), 1);
}

TEST(PlaPaths, RectangleInfillIsOneZigzagAtLineWidthSpacing) {
    const std::vector<Toolpath> infill =
        with_role(pla_layer_paths(test::rectangle_outline(), 0), PathRole::infill);
    ASSERT_EQ(infill.size(), 1u);  // convex: every scan segment joins the zigzag
    expect_scan_spacing(infill, 0);
    // Region left for the infill: y in [1.6, 8.4], 6.8 mm: 9 lines 0.8 apart, centred.
    std::set<long> rows;
    for (const Eigen::Vector2d& p : infill[0].points) rows.insert(std::lround(p.y() * 1e4));
    EXPECT_EQ(rows.size(), 9u);
    EXPECT_EQ(*rows.begin(), 18000);  // 1.6 + (6.8 - 6.4) / 2
}

TEST(PlaPaths, HoledRectangleRingsAroundHoleAndInfillOutsideIt) {
    expect_rings_and_infill(test::holed_rectangle_outline(), 2);
    const std::vector<Toolpath> infill =
        with_role(pla_layer_paths(test::holed_rectangle_outline(), 1), PathRole::infill);
    expect_scan_spacing(infill, 45);
}

TEST(PlaPaths, LShapeRingsFollowTheInnerCorner) {
    expect_rings_and_infill(test::l_shape_outline(), 1);
    for (int layer = 0; layer < 4; ++layer)
        expect_infill_inside(
            with_role(pla_layer_paths(test::l_shape_outline(), layer), PathRole::infill),
            test::l_shape_outline(), 2 * w);
}

TEST(PlaPaths, TwoSquaresArePrintedOneAfterTheOther) {
    const LayerOutline outline = test::two_squares_outline();
    expect_rings_and_infill(outline, 2);
    const std::vector<Toolpath> paths = pla_layer_paths(outline, 0);
    // Island of each path by x; the order switches island exactly once.
    int switches = 0;
    for (std::size_t i = 1; i < paths.size(); ++i)
        switches += (paths[i].points[0].x() < 15) != (paths[i - 1].points[0].x() < 15);
    EXPECT_EQ(switches, 1);
    EXPECT_LT(paths.front().points.front().x(), 15);  // nearest to the start at the origin
}

TEST(PlaPaths, InfillDirectionTurns45DegreesPerLayer) {
    const LayerOutline outline = test::holed_rectangle_outline();
    for (int layer = 0; layer < 5; ++layer) {
        const std::vector<Toolpath> infill =
            with_role(pla_layer_paths(outline, layer), PathRole::infill);
        // The longest scan piece runs along the layer's direction.
        const std::vector<test::Piece> pieces = test::long_pieces(infill, 3 * w);
        ASSERT_FALSE(pieces.empty());
        const double want = std::fmod(45.0 * layer, 180);
        for (const test::Piece& piece : pieces) {
            const double got = test::direction_deg(piece);
            if (std::abs(got - want) > 1e-6) {
                // Only boundary links may run elsewhere, and they follow the inset outline.
                EXPECT_LT((piece.b - piece.a).norm(), 4 * w * 1.5) << "layer " << layer;
            }
        }
        expect_scan_spacing(infill, 45.0 * layer);
    }
}

TEST(PlaPaths, NoPerimetersFillsFromHalfAWidth) {
    PlaPathOptions options;
    options.perimeters = 0;
    const std::vector<Toolpath> paths = pla_layer_paths(test::rectangle_outline(), 0, options);
    ASSERT_FALSE(paths.empty());
    EXPECT_TRUE(with_role(paths, PathRole::perimeter).empty());
    expect_infill_inside(paths, test::rectangle_outline(), w / 2);
}

TEST(PlaPaths, NarrowPartKeepsOnlyTheRingsThatFit) {
    // 2 mm wide: ring 0 at 0.4 fits, ring 1 at 1.2 does not, nor does the infill.
    const std::vector<Toolpath> paths = pla_layer_paths({{test::rectangle(0, 0, 20, 2)}}, 0);
    EXPECT_EQ(with_role(paths, PathRole::perimeter).size(), 1u);
    EXPECT_TRUE(with_role(paths, PathRole::infill).empty());
}

TEST(PlaPaths, RejectsBadInput) {
    PlaPathOptions options;
    options.line_width_mm = 0;
    EXPECT_THROW(pla_layer_paths(test::rectangle_outline(), 0, options), std::invalid_argument);
    options = {};
    options.perimeters = -1;
    EXPECT_THROW(pla_layer_paths(test::rectangle_outline(), 0, options), std::invalid_argument);
    EXPECT_THROW(pla_layer_paths({{{{0, 0}, {1, 0}}}}, 0), std::invalid_argument);
    EXPECT_THROW(pla_layer_paths({{{{0, 0}, {1, 0}, {0, NAN}}}}, 0), std::invalid_argument);
}

TEST(PathOrder, EntersNearestAndReversesOpenPaths) {
    std::vector<Toolpath> paths{{PathRole::infill, false, {{10, 0}, {20, 0}}},
                                {PathRole::infill, false, {{5, 0}, {1, 0}}},
                                {PathRole::perimeter, true, {{30, 0}, {30, 5}, {21, 0}}}};
    const std::vector<Toolpath> ordered = order_nearest(paths, {0, 0});
    ASSERT_EQ(ordered.size(), 3u);
    EXPECT_EQ(ordered[0].points.front(), Eigen::Vector2d(1, 0));  // reversed
    EXPECT_EQ(ordered[1].points.front(), Eigen::Vector2d(10, 0));
    EXPECT_EQ(ordered[2].points.front(), Eigen::Vector2d(21, 0));  // rotated ring
    EXPECT_DOUBLE_EQ(path_length(ordered[2]), 5 + std::hypot(9, 5) + 9);
}

}  // namespace
}  // namespace fibrecell::planner
