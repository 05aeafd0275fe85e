// The stripes of the field-dense strategy, measured from their points alone: where they run, how
// far apart, and whether they are whole.
#include "planner/fibre/stripe_pattern.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace fibrecell::planner;
using fibrecell::planner::layer_test::centre;
using fibrecell::planner::layer_test::grid_layer;

namespace {

// The y of each stripe that crosses x = 15 (the middle of a 30 mm wide grid), ascending.
std::vector<double> stripe_heights(const StripePattern& p) {
    std::vector<double> ys;
    for (const Polyline& s : p.stripes)
        for (std::size_t k = 0; k + 1 < s.points.size(); ++k) {
            const Eigen::Vector2d a = s.points[k], b = s.points[k + 1];
            if ((a.x() - 15) * (b.x() - 15) > 0 || a.x() == b.x()) continue;
            ys.push_back(a.y() + (15 - a.x()) / (b.x() - a.x()) * (b.y() - a.y()));
        }
    std::sort(ys.begin(), ys.end());
    return ys;
}

}  // namespace

TEST(StripePattern, AUniformFieldGivesStraightStripesOnePeriodApartAcrossTheWholeLayer) {
    // Triangles 2 mm wide: coarser than the 1.2 mm period, as the layers' meshes are.
    const LayerMesh m = grid_layer(30, 20, 15, 10);
    const std::vector<Eigen::Vector2d> along(m.triangles.size(), Eigen::Vector2d(1, 0));
    const StripePattern p = stripe_pattern(m, along, {.spacing_mm = 1.2});
    EXPECT_EQ(p.singular_triangles, 0u);
    // Each stripe runs the layer's width along x, straight.
    for (const Polyline& s : p.stripes) {
        EXPECT_FALSE(s.closed);
        EXPECT_NEAR(std::abs(s.points.back().x() - s.points.front().x()), 30, 1e-6);
        for (const auto& q : s.points) EXPECT_NEAR(q.y(), s.points.front().y(), 1e-6);
    }
    const std::vector<double> ys = stripe_heights(p);
    ASSERT_EQ(ys.size(), p.stripes.size());
    EXPECT_NEAR(static_cast<double>(ys.size()), 20 / 1.2, 1.0);
    for (std::size_t k = 1; k < ys.size(); ++k) EXPECT_NEAR(ys[k] - ys[k - 1], 1.2, 1e-6) << "stripe " << k;
}

TEST(StripePattern, ADirectionGivenEitherWayRoundGivesTheSameStripes) {
    // The stress direction is a line, not an arrow: flipping half the faces changes nothing.
    const LayerMesh m = grid_layer(30, 20, 15, 10);
    std::vector<Eigen::Vector2d> along(m.triangles.size(), Eigen::Vector2d(1, 0.2));
    const StripePattern straight = stripe_pattern(m, along, {.spacing_mm = 1.0});
    for (std::size_t f = 0; f < along.size(); f += 2) along[f] = -along[f];
    const StripePattern flipped = stripe_pattern(m, along, {.spacing_mm = 1.0});
    EXPECT_EQ(flipped.singular_triangles, 0u);
    const std::vector<double> a = stripe_heights(straight), b = stripe_heights(flipped);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 10u);
    // The same spacing (the phase itself may sit anywhere).
    for (std::size_t k = 1; k < a.size(); ++k)
        EXPECT_NEAR(b[k] - b[k - 1], a[k] - a[k - 1], 1e-3) << "stripe " << k;
}

TEST(StripePattern, ACircularFieldGivesClosedRingsOnePeriodApart) {
    const Eigen::Vector2d o(20, 20);
    const LayerMesh m = grid_layer(40, 40, 40, 40, [&](const Eigen::Vector2d& c) {
        return (c - o).norm() > 5 && (c - o).norm() < 19;
    });
    std::vector<Eigen::Vector2d> along;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        const Eigen::Vector2d r = centre(m, f) - o;
        along.emplace_back(-r.y(), r.x());
    }
    const StripePattern p = stripe_pattern(m, along, {.spacing_mm = 1.5});
    std::vector<double> radii;
    for (const Polyline& s : p.stripes) {
        if (!s.closed) continue;
        double r = 0;
        for (const auto& q : s.points) r += (q - o).norm();
        r /= static_cast<double>(s.points.size());
        for (const auto& q : s.points) EXPECT_NEAR((q - o).norm(), r, 0.15) << "a ring is not round";
        radii.push_back(r);
    }
    // 14 mm of annulus at 1.5 mm: 9 rings, each closed, 1.5 mm apart.
    std::sort(radii.begin(), radii.end());
    ASSERT_GE(radii.size(), 8u);
    for (std::size_t k = 1; k < radii.size(); ++k) EXPECT_NEAR(radii[k] - radii[k - 1], 1.5, 0.1);
}
