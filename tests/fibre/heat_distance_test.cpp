#include "planner/fibre/heat_distance.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fibrecell::planner;
using fibrecell::planner::testing::grid_layer;

TEST(HeatDistance, DistanceFromAStraightEdgeIsMetric) {
    const LayerMesh m = grid_layer(40, 20, 40, 20);
    std::vector<int> left;
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v)
        if (m.vertices[v].x() == 0) left.push_back(v);
    const auto d = heat_distance(m, left);
    // Everywhere, including the corners where the source edge meets the free boundary (with
    // equal heat at every source vertex the corners ran hot and were 0.4 mm off on this 1 mm
    // grid). Within 5 mm, where Section 4.4 draws its curves, to a tenth of the grid.
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v) {
        const Eigen::Vector2d p = m.vertices[v];
        EXPECT_NEAR(d[v], p.x(), p.x() <= 5 ? 0.1 : 0.015 * p.x() + 0.15) << "at " << p.transpose();
    }
}

TEST(HeatDistance, DistanceFromAHoleGrowsWithTheRadius) {
    const Eigen::Vector2d o(20, 20);
    const LayerMesh m =
        grid_layer(40, 40, 80, 80, [&](const Eigen::Vector2d& c) { return (c - o).norm() > 5.0; });
    // Sources: the vertices of the staircase hole's rim (nearest the centre).
    std::vector<int> rim;
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v)
        if ((m.vertices[v] - o).norm() < 5.6) rim.push_back(v);
    const auto d = heat_distance(m, rim);
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v) {
        const double r = (m.vertices[v] - o).norm();
        if (r < 8 || r > 18) continue;  // away from the jagged rim and the square's corners
        EXPECT_NEAR(d[v], r - 5.3, 0.6) << "at r = " << r;
    }
}

TEST(HeatDistance, PiecesWithoutASourceAreUnreachable) {
    const LayerMesh m = grid_layer(
        30, 10, 15, 5, [](const Eigen::Vector2d& c) { return c.x() < 10 || c.x() > 20; });
    const auto d = heat_distance(m, {0});
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v) {
        if (m.vertices[v].x() > 20) {
            EXPECT_TRUE(std::isinf(d[v]));
        } else if (m.vertices[v].x() < 10) {
            EXPECT_TRUE(std::isfinite(d[v]));
        }
    }
    EXPECT_DOUBLE_EQ(d[0], 0.0);
}
