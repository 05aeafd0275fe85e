// The per-boundary figures of report.json on a square layer whose rings are placed by hand.

#include "planner/plan/boundary_fibre_stats.hpp"
#include "../fibre/layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fibrecell::planner;

namespace {

// A 40 x 40 mm square in 1 mm cells and its outline edges, counter-clockwise from (0, 0).
struct Square {
    static constexpr int n = 40;
    LayerMesh mesh = fibrecell::planner::layer_test::grid_layer(n, n, n, n);
    std::vector<std::array<int, 2>> edges;

    Square() {
        auto id = [](int i, int j) { return i + (n + 1) * j; };
        for (int k = 0; k < n; ++k) {
            edges.push_back({id(k, 0), id(k + 1, 0)});
            edges.push_back({id(n, k), id(n, k + 1)});
            edges.push_back({id(k, n), id(k + 1, n)});
            edges.push_back({id(0, k), id(0, k + 1)});
        }
    }
};

// The square inset by d as a closed fibre-boundary ring.
Toolpath ring_at(double d) {
    const double lo = d, hi = Square::n - d;
    return {PathRole::fibre_boundary, true, {{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}}};
}

}  // namespace

// Fibre counts within 1.5W + 0.2 mm = 1.7 mm of the edge; the edge is judged every 0.5 mm.
constexpr double kReach = 1.7, kTolerance = 8 * 0.25 / 160;

// How far past the end of a path at 1.5 mm from an edge the edge still has it within reach.
const double past_end = std::sqrt(kReach * kReach - 1.5 * 1.5);  // 0.8 mm

TEST(BoundaryFibreStats, ARingAtOneAndAHalfWCoversItsBoundary) {
    const Square sq;
    const BoundaryFibreStats s = boundary_fibre_stats(sq.mesh, sq.edges, {ring_at(1.5)}, 1.0);
    EXPECT_NEAR(s.edge_mm, 160.0, 1e-9);
    // All but the square's corners, which are 1.5 sqrt(2) from the ring's: 1.5 - 0.8 mm of
    // either edge at each.
    EXPECT_NEAR(s.coverage(), 1.0 - 8 * (1.5 - past_end) / 160, kTolerance);
    EXPECT_EQ(s.rings, 1);
    EXPECT_NEAR(s.ring_mm, 4 * 37.0, 1e-9);
    EXPECT_NEAR(s.ring_distance_quantile(0.5), 1.5, 1e-9);
    EXPECT_NEAR(s.ring_distance_quantile(0.05), 1.5, 1e-9);
}

TEST(BoundaryFibreStats, FibreFartherThanARingDoesNotCount) {
    const Square sq;
    // At 3W the ring belongs to no boundary here, and nothing lies alongside the edge.
    const BoundaryFibreStats s = boundary_fibre_stats(sq.mesh, sq.edges, {ring_at(3.0)}, 1.0);
    EXPECT_EQ(s.rings, 0);
    EXPECT_EQ(s.coverage(), 0.0);
    EXPECT_EQ(s.ring_distance_quantile(0.5), 0.0);
}

TEST(BoundaryFibreStats, AStressPathAlongPartOfTheEdgeCoversThatPart) {
    const Square sq;
    // 30 mm along the bottom at 1.5 mm, as a ring joined into a stress path would lie.
    const Toolpath joined{PathRole::fibre, false, {{5, 1.5}, {35, 1.5}}};
    BoundaryFibreStats s = boundary_fibre_stats(sq.mesh, sq.edges, {joined}, 1.0);
    const double along = 30 + 2 * past_end;
    EXPECT_NEAR(s.coverage(), along / 160, kTolerance);
    EXPECT_EQ(s.rings, 0);  // not a fibre-boundary path
    // Two layers add up.
    s += boundary_fibre_stats(sq.mesh, sq.edges, {ring_at(1.5)}, 1.0);
    EXPECT_NEAR(s.coverage(), (along + 160 - 8 * (1.5 - past_end)) / 320, kTolerance);
    EXPECT_EQ(s.rings, 1);
}

TEST(BoundaryFibreStats, JoinsAndJoinedRingsCountForTheBoundaryTheyAreBeside) {
    const Square sq;
    // Links 1.5 and 2.9 mm from the bottom edge are its joins; one in the middle is not. A joined
    // ring's point at 1.5 mm belongs here, one 2.5 mm in (beyond 2W) does not.
    const std::vector<Eigen::Vector2d> links = {{10, 1.5}, {20, 2.9}, {20, 20}};
    const std::vector<Eigen::Vector2d> rings = {{1.5, 30}, {2.5, 20}};
    const BoundaryFibreStats s =
        boundary_fibre_stats(sq.mesh, sq.edges, {ring_at(1.5)}, 1.0, {links, rings});
    EXPECT_EQ(s.joins, 2);
    EXPECT_EQ(s.rings_joined, 1);
    BoundaryFibreStats sum = s;
    sum += s;
    EXPECT_EQ(sum.joins, 4);
    EXPECT_EQ(sum.rings_joined, 2);
}
