// Baseline fibre strategy: boundary rings at W/2 + i*W, zigzag at spacing W turned 45 degrees per
// CCF layer, paths shorter than the cutter distance dropped and counted.

#include "planner/toolpaths/contour_zigzag.hpp"

#include "planner/toolpaths/path_order.hpp"
#include "toolpath_test_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>

namespace fibrecell::planner {
namespace {

using test::distance_to_outline;
using test::with_role;

constexpr double W = 1.0;

LayerOutline plate() {
    return {{test::rectangle(0, 0, 60, 30)}};
}

// A plate and, 20 mm away, a 5 x 5 island too small for any fibre path.
LayerOutline plate_with_island() {
    return {{test::rectangle(0, 0, 60, 30), test::rectangle(80, 0, 85, 5)}};
}

TEST(ContourZigzag, BoundaryRingsAtHalfSpacingPlusPitch) {
    const LayerOutline outline = plate();
    const FibreLayerPaths result = contour_zigzag_paths(outline, 0);
    const std::vector<Toolpath> rings = with_role(result.paths, PathRole::fibre_boundary);
    ASSERT_EQ(rings.size(), 2u);
    std::set<long> distances;
    for (const Toolpath& ring : rings) {
        EXPECT_TRUE(ring.closed);
        const double d = distance_to_outline(ring.points.front(), outline);
        for (const Eigen::Vector2d& p : ring.points)
            EXPECT_NEAR(distance_to_outline(p, outline), d, 1e-3);
        distances.insert(std::lround(d * 1e3));
    }
    // W/2 and W/2 + W, plus 2.5 arc tolerances (0.002 mm) for the round joins' chords.
    EXPECT_EQ(distances, (std::set<long>{505, 1505}));
}

TEST(ContourZigzag, ZigzagAtSpacingWInsideTheRings) {
    const LayerOutline outline = plate();
    const std::vector<Toolpath> fibre =
        with_role(contour_zigzag_paths(outline, 0).paths, PathRole::fibre);
    ASSERT_EQ(fibre.size(), 1u);  // one long path over the convex plate
    EXPECT_FALSE(fibre[0].closed);
    std::set<long> rows;
    for (const Eigen::Vector2d& p : fibre[0].points) {
        EXPECT_GE(distance_to_outline(p, outline), 2.5 * W);
        rows.insert(std::lround(p.y() * 1e4));
    }
    // y in [2.5, 27.5], a whole W inside the inner ring at 1.5W: 25 lines 1 mm apart (24 mm)
    // centred: 3 ... 27 (the margin for round joins' chords is too small to show).
    ASSERT_EQ(rows.size(), 25u);
    EXPECT_EQ(*rows.begin(), 30000);
    long previous = *rows.begin() - 10000;
    for (long row : rows) {
        EXPECT_EQ(row - previous, 10000);
        previous = row;
    }
}

TEST(ContourZigzag, DirectionTurns45DegreesBetweenCcfLayers) {
    const LayerOutline outline = plate();
    for (int layer = 0; layer < 4; ++layer) {
        const std::vector<Toolpath> fibre =
            with_role(contour_zigzag_paths(outline, layer).paths, PathRole::fibre);
        ASSERT_FALSE(fibre.empty());
        // The longest straight piece is a scan segment: it runs along the layer's direction.
        const std::vector<test::Piece> pieces = test::long_pieces(fibre, 0);
        const auto longest = std::max_element(pieces.begin(), pieces.end(),
                                              [](const test::Piece& a, const test::Piece& b) {
                                                  return (a.b - a.a).norm() < (b.b - b.a).norm();
                                              });
        EXPECT_NEAR(test::direction_deg(*longest), std::fmod(45.0 * layer, 180), 1e-6);
    }
}

TEST(ContourZigzag, DropsAndCountsPathsShorterThanTheCutterDistance) {
    const FibreLayerPaths result = contour_zigzag_paths(plate_with_island(), 0);
    // The island: rings of 16 mm and 8 mm (no room for a zigzag W inside them), both shorter
    // than 42 mm.
    EXPECT_EQ(result.dropped_short, 2);
    EXPECT_EQ(result.paths.size(), 3u);  // the plate's two rings and its zigzag
    for (const Toolpath& path : result.paths) {
        EXPECT_GE(path_length(path), 42.0);
        for (const Eigen::Vector2d& p : path.points) EXPECT_LT(p.x(), 60);
    }
}

TEST(ContourZigzag, NoPathShorterThanTheCutterOnAnyShape) {
    for (const LayerOutline& outline :
         {test::holed_rectangle_outline(), test::l_shape_outline(), test::two_squares_outline()})
        for (int layer = 0; layer < 3; ++layer) {
            const FibreLayerPaths result = contour_zigzag_paths(outline, layer);
            for (const Toolpath& path : result.paths) {
                EXPECT_GE(path_length(path), 42.0);
                for (const Eigen::Vector2d& p : path.points)
                    EXPECT_TRUE(test::inside(p, outline)) << p.transpose();
            }
        }
}

// The fair baseline keeps W like any fibre: sample the zigzag every W/8 and measure each point's
// distance to every ring, on shapes with holes and concave corners.
TEST(ContourZigzag, ZigzagNeverComesWithinWOfARing) {
    for (const LayerOutline& outline : {test::holed_rectangle_outline(), test::l_shape_outline()})
        for (int layer = 0; layer < 3; ++layer) {
            const FibreLayerPaths result = contour_zigzag_paths(outline, layer);
            const std::vector<Toolpath> rings = with_role(result.paths, PathRole::fibre_boundary);
            const std::vector<Toolpath> zigzag = with_role(result.paths, PathRole::fibre);
            ASSERT_FALSE(rings.empty());
            ASSERT_FALSE(zigzag.empty());
            double nearest = 1e9;
            for (const Toolpath& path : zigzag)
                for (std::size_t i = 0; i + 1 < path.points.size(); ++i)
                    for (int k = 0; k < 8; ++k) {
                        const Eigen::Vector2d p =
                            path.points[i] + (path.points[i + 1] - path.points[i]) * (k / 8.0);
                        for (const Toolpath& ring : rings)
                            nearest = std::min(nearest, distance_to_outline(p, {{ring.points}}));
                    }
            EXPECT_GE(nearest, W - 1e-6) << "layer " << layer;
        }
}

TEST(ContourZigzag, OptionsFromTheJob) {
    PlannerSpec planner;
    planner.fibre_spacing_mm = 1.5;
    const ContourZigzagOptions options = contour_zigzag_options(planner, 30);
    EXPECT_EQ(options.fibre_spacing_mm, 1.5);
    EXPECT_EQ(options.cutter_distance_mm, 30);
}

TEST(ContourZigzag, RejectsBadInput) {
    ContourZigzagOptions options;
    options.fibre_spacing_mm = -1;
    EXPECT_THROW(contour_zigzag_paths(plate(), 0, options), std::invalid_argument);
    options = {};
    options.cutter_distance_mm = NAN;
    EXPECT_THROW(contour_zigzag_paths(plate(), 0, options), std::invalid_argument);
}

}  // namespace
}  // namespace fibrecell::planner
