#include "planner/layers/outline.hpp"
#include "planner/layers/slice.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include "layer_checks.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace fibrecell::planner;
using namespace fibrecell::planner::test;

namespace {

// Unit squares at the given lower-left corners, two counter-clockwise triangles each, sharing
// vertices at equal positions.
LayerMesh squares(const std::vector<Eigen::Vector2d>& corners) {
    LayerMesh m;
    auto vertex = [&](const Eigen::Vector2d& p) {
        for (int i = 0; i < static_cast<int>(m.vertices.size()); ++i)
            if (m.vertices[i] == p) return i;
        m.vertices.push_back(p);
        return static_cast<int>(m.vertices.size()) - 1;
    };
    for (const auto& c : corners) {
        const int a = vertex(c), b = vertex(c + Eigen::Vector2d(1, 0));
        const int d = vertex(c + Eigen::Vector2d(1, 1)), e = vertex(c + Eigen::Vector2d(0, 1));
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({a, d, e});
        m.triangle_tet.insert(m.triangle_tet.end(), {0, 0});
    }
    return m;
}

std::vector<double> sorted_areas(const LayerOutline& outline) {
    std::vector<double> areas;
    for (const auto& loop : outline.loops) {
        EXPECT_FALSE(loop_has_repeated_point(loop));
        areas.push_back(signed_area(loop));
    }
    std::sort(areas.begin(), areas.end());
    return areas;
}

}  // namespace

TEST(Outline, SquareIsOneCounterClockwiseLoop) {
    const LayerOutline outline = layer_outline(squares({{0, 0}}));
    ASSERT_EQ(outline.loops.size(), 1u);
    EXPECT_EQ(outline.loops[0].size(), 4u);
    EXPECT_DOUBLE_EQ(signed_area(outline.loops[0]), 1.0);
}

TEST(Outline, SquaresTouchingAtACornerAreTwoLoops) {
    // Bow tie: the shared corner (1, 1) is a non-manifold boundary vertex.
    const LayerOutline outline = layer_outline(squares({{0, 0}, {1, 1}}));
    ASSERT_EQ(outline.loops.size(), 2u);
    EXPECT_EQ(sorted_areas(outline), (std::vector<double>{1.0, 1.0}));
    for (const auto& loop : outline.loops) EXPECT_EQ(loop.size(), 4u);
}

TEST(Outline, HoleTouchingTheOuterBoundaryAtACornerIsItsOwnLoop) {
    // 3 x 3 squares without (0, 0) and (1, 1): the hole touches the notch at (1, 1).
    std::vector<Eigen::Vector2d> corners;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (!(i == j && i < 2)) corners.emplace_back(i, j);
    const LayerOutline outline = layer_outline(squares(corners));
    ASSERT_EQ(outline.loops.size(), 2u);
    EXPECT_EQ(sorted_areas(outline), (std::vector<double>{-1.0, 8.0}));
}

TEST(Outline, SlicedCornerTouchingBlocks) {
    StructuredMeshOptions o;
    o.size = {2, 2, 1};
    o.cells = {2, 2, 1};
    o.keep_cell = [](const Eigen::Vector3d& c) { return (c.x() < 1) == (c.y() < 1); };
    const LayerMesh layer = slice_tet_mesh(structured_tet_mesh(o), 0.5);
    const LayerOutline outline = layer_outline(layer);
    ASSERT_EQ(outline.loops.size(), 2u);
    const auto areas = sorted_areas(outline);
    EXPECT_NEAR(areas[0], 1.0, 1e-12);
    EXPECT_NEAR(areas[1], 1.0, 1e-12);
}

TEST(Outline, RejectsBadIndicesAndInconsistentOrientation) {
    LayerMesh m = squares({{0, 0}});
    m.triangles[1] = {0, 1, 7};
    EXPECT_THROW(layer_outline(m), std::invalid_argument);
    m = squares({{0, 0}, {1, 0}});
    std::swap(m.triangles[3][1], m.triangles[3][2]);  // one triangle clockwise
    EXPECT_THROW(layer_outline(m), std::invalid_argument);
}
