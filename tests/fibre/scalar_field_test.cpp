#include "planner/fibre/scalar_field.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace fibrecell::planner;
using fibrecell::planner::layer_test::centre;
using fibrecell::planner::layer_test::grid_layer;

TEST(ScalarField, UniformTensionAlongXGivesLevelLinesAlongX) {
    const LayerMesh m = grid_layer(30, 10, 15, 5);
    const std::vector<Eigen::Vector2d> u(m.triangles.size(), Eigen::Vector2d(4.0, 0.0));
    const auto s = scalar_field(m, u);
    // grad s = rot90(u) = (0, 4) exactly: s depends on y only, so its isocurves run along x.
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        const Eigen::Vector2d g = triangle_gradient(m, s, f);
        EXPECT_NEAR(g.x(), 0.0, 1e-9);
        EXPECT_NEAR(g.y(), 4.0, 1e-9);
    }
    EXPECT_NEAR(s[0], 0.0, 1e-12);  // the pinned vertex
}

TEST(ScalarField, CircularFieldGivesConcentricLevelLines) {
    // u tangential around the centre with |u| = 1 (p = 0): s = -r + const, circles.
    const Eigen::Vector2d o(20, 20);
    const LayerMesh m = grid_layer(40, 40, 40, 40, [&](const Eigen::Vector2d& c) {
        return (c - o).norm() > 5 && (c - o).norm() < 19;
    });
    std::vector<Eigen::Vector2d> u;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        const Eigen::Vector2d d = centre(m, f) - o;
        u.emplace_back(Eigen::Vector2d(-d.y(), d.x()).normalized());
    }
    const auto s = scalar_field(m, u);
    double lo = 1e9, hi = -1e9;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
        const double r = (m.vertices[v] - o).norm();
        if (r < 5.5 || r > 18.5) continue;  // vertices of kept cells only
        lo = std::min(lo, s[v] + r);
        hi = std::max(hi, s[v] + r);
    }
    EXPECT_LT(hi - lo, 0.15) << "s + r should be constant to within the mesh resolution (1 mm)";
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
        const Eigen::Vector2d g = triangle_gradient(m, s, f).normalized();
        const Eigen::Vector2d radial = (centre(m, f) - o).normalized();
        EXPECT_LT(g.dot(radial), -0.97) << "face " << f;  // the isocurves follow the circles
    }
}

TEST(ScalarField, DensityFollowsTheMagnitudeOfU) {
    // Fibres along x with |u| = 1 below y = 10 and 3 above: s rises three times as fast there,
    // so isocurves at a fixed isovalue step lie three times closer where the stress is higher.
    // (rot90(u) = (0, g(y)) is a gradient, so the fit is exact.)
    const LayerMesh m = grid_layer(20, 20, 20, 20);
    std::vector<Eigen::Vector2d> u;
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f)
        u.emplace_back(centre(m, f).y() < 10 ? 1.0 : 3.0, 0.0);
    const auto s = scalar_field(m, u);
    auto at = [&](int i, int j) { return s[i + 21 * j]; };
    EXPECT_NEAR(at(7, 10) - at(7, 0), 10.0, 1e-9);
    EXPECT_NEAR(at(13, 20) - at(13, 10), 30.0, 1e-9);
}

TEST(ScalarField, SeparatePiecesAreEachPinned) {
    const LayerMesh m = grid_layer(
        30, 10, 15, 5, [](const Eigen::Vector2d& c) { return c.x() < 10 || c.x() > 20; });
    const std::vector<Eigen::Vector2d> u(m.triangles.size(), Eigen::Vector2d(1.0, 0.0));
    const auto s = scalar_field(m, u);
    for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f)
        EXPECT_NEAR(triangle_gradient(m, s, f).y(), 1.0, 1e-9);
}

TEST(ScalarField, NoTensionGivesAFlatField) {
    const LayerMesh m = grid_layer(10, 10, 5, 5);
    const std::vector<Eigen::Vector2d> u(m.triangles.size(), Eigen::Vector2d::Zero());
    for (double v : scalar_field(m, u)) EXPECT_NEAR(v, 0.0, 1e-12);
}
