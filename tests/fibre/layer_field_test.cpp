#include "planner/fibre/layer_field.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;
using fibrecell::planner::layer_test::centre;
using fibrecell::planner::layer_test::grid_layer;

namespace {

struct TetValues {
    std::vector<Eigen::Vector3d> v_e;
    std::vector<double> sigma_e;
    std::vector<std::uint8_t> defined;
};

TetValues uniform(std::size_t n, const Eigen::Vector3d& v, double sigma) {
    return {std::vector<Eigen::Vector3d>(n, v), std::vector<double>(n, sigma),
            std::vector<std::uint8_t>(n, 1)};
}

}  // namespace

TEST(LayerField, UniformTensionGivesUniformU) {
    const LayerMesh m = grid_layer(20, 10, 10, 5);
    const TetValues t = uniform(m.triangles.size(), Eigen::Vector3d(1, 0, 0.1).normalized(), 8.0);
    const LayerField f = layer_field(m, t.v_e, t.sigma_e, t.defined, {.p = 1.0});
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        EXPECT_NEAR(f.sigma_f[i], 8.0, 1e-12);
        EXPECT_NEAR(f.u_f[i].x(), 8.0, 1e-12);  // sigma^p along the projected, normalised v
        EXPECT_NEAR(f.u_f[i].y(), 0.0, 1e-12);
    }
    const LayerField uniform_density = layer_field(m, t.v_e, t.sigma_e, t.defined, {.p = 0.0});
    EXPECT_NEAR(uniform_density.u_f[3].norm(), 1.0, 1e-12);
}

TEST(LayerField, UndefinedAndVerticalDirectionsAreFilledFromTheirSurroundings) {
    const LayerMesh m = grid_layer(20, 20, 10, 10);
    TetValues t = uniform(m.triangles.size(), Eigen::Vector3d::UnitY(), 2.0);
    std::size_t holes = 0;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const Eigen::Vector2d c = centre(m, static_cast<int>(i));
        if ((c - Eigen::Vector2d(10, 10)).norm() < 4) {
            t.defined[i] = 0;                     // removed by the incompatibility filter
            t.v_e[i] = Eigen::Vector3d(1, 0, 0);  // whatever it was, it must not show
            ++holes;
        } else if ((c - Eigen::Vector2d(3, 3)).norm() < 2) {
            t.v_e[i] = Eigen::Vector3d::UnitZ();  // vertical: no in-plane information
        }
    }
    ASSERT_GT(holes, 10u);
    const LayerField f = layer_field(m, t.v_e, t.sigma_e, t.defined);
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        ASSERT_GT(f.u_f[i].norm(), 0.0) << "face " << i << " left empty";
        EXPECT_NEAR(f.u_f[i].normalized().y(), 1.0, 1e-9) << "face " << i;
    }
}

TEST(LayerField, SmoothingAveragesSigmaButHoldsTheMaximum) {
    const LayerMesh m = grid_layer(10, 10, 10, 10);
    TetValues t = uniform(m.triangles.size(), Eigen::Vector3d::UnitX(), 1.0);
    t.sigma_e[57] = 100.0;  // a spike
    const LayerField f = layer_field(m, t.v_e, t.sigma_e, t.defined, {.smoothing_iterations = 50});
    EXPECT_EQ(f.fixed_face, 57);
    EXPECT_DOUBLE_EQ(f.sigma_f[57], 100.0);
    // Diffused around it: neighbours raised, far faces barely touched, nothing above the spike.
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        EXPECT_LE(f.sigma_f[i], 100.0);
        EXPECT_GE(f.sigma_f[i], 1.0 - 1e-12);
    }
    const auto nb = triangle_neighbours(m);
    for (int g : nb[57]) EXPECT_GT(f.sigma_f[g], 10.0);
    // No smoothing: the input comes through unchanged.
    const LayerField raw = layer_field(m, t.v_e, t.sigma_e, t.defined, {.smoothing_iterations = 0});
    EXPECT_DOUBLE_EQ(raw.sigma_f[58], 1.0);
}

TEST(LayerField, TriangleNeighboursShareAnEdge) {
    const LayerMesh m = grid_layer(2, 2, 2, 2);
    const auto nb = triangle_neighbours(m);
    std::size_t pairs = 0;
    for (std::size_t f = 0; f < nb.size(); ++f) {
        for (int g : nb[f]) {
            int shared = 0;
            for (int a : m.triangles[f])
                for (int b : m.triangles[g]) shared += a == b;
            EXPECT_EQ(shared, 2);
            ++pairs;
        }
    }
    // 8 triangles in a 2x2 grid have 16 interior edges... counted from both sides.
    EXPECT_EQ(pairs, 2u * 8);
}

TEST(LayerField, SigmaCapLimitsTheSingularityNotTheDirection) {
    const LayerMesh m = grid_layer(10, 10, 10, 10);
    TetValues t = uniform(m.triangles.size(), Eigen::Vector3d::UnitX(), 2.0);
    t.sigma_e[57] = 1000.0;  // a singularity in one face
    const LayerField capped =
        layer_field(m, t.v_e, t.sigma_e, t.defined,
                    {.smoothing_iterations = 0, .p = 1.0, .sigma_cap_percentile = 99.0});
    for (const auto& u : capped.u_f) EXPECT_NEAR(u.x(), 2.0, 1e-12);  // the 99th percentile is 2
    const LayerField paper =
        layer_field(m, t.v_e, t.sigma_e, t.defined, {.smoothing_iterations = 0, .p = 1.0});
    EXPECT_NEAR(paper.u_f[57].x(), 1000.0, 1e-12);
}
