// The constant-strain tet on its own: shape functions, stiffness and stress.

#include "planner/fea/tet_element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

using namespace fibrecell::planner;

namespace {

// A skewed, positively oriented tet.
TetMesh skewed_tet() {
    TetMesh m;
    m.vertices = {{0.3, -0.2, 0.1}, {2.1, 0.4, -0.3}, {0.5, 1.7, 0.2}, {0.2, 0.6, 1.4}};
    m.tets = {{0, 1, 2, 3}};
    return m;
}

Eigen::Matrix<double, 12, 12> element_stiffness(const TetGeometry& g, const Lame& lame) {
    Eigen::Matrix<double, 12, 12> k;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) k.block<3, 3>(3 * a, 3 * b) = stiffness_block(g, lame, a, b);
    return k;
}

}  // namespace

TEST(TetElement, GradientsReproduceALinearField) {
    const TetMesh m = skewed_tet();
    const TetGeometry g = tet_geometry(m, m.tets[0]);
    EXPECT_NEAR(g.volume, signed_volume(m, m.tets[0]), 1e-14);
    const Eigen::Vector3d slope(0.7, -1.3, 2.2);  // f(x) = slope . x + 4
    Eigen::Vector3d grad = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) grad += (slope.dot(m.vertices[a]) + 4) * g.grad[a];
    EXPECT_LT((grad - slope).norm(), 1e-12);
}

TEST(TetElement, StiffnessIsSymmetricAndBlindToRigidMotion) {
    const TetMesh m = skewed_tet();
    const Lame lame = lame_parameters({3500, 0.36});
    const Eigen::Matrix<double, 12, 12> k = element_stiffness(tet_geometry(m, m.tets[0]), lame);
    EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
    const Eigen::Vector3d spin(0.3, -0.5, 0.8);
    const Eigen::Vector3d shift(1, 2, -3);
    Eigen::Matrix<double, 12, 1> u;
    for (int a = 0; a < 4; ++a) u.segment<3>(3 * a) = shift + spin.cross(m.vertices[a]);
    EXPECT_LT((k * u).norm(), 1e-12 * k.norm() * u.norm());
    // Six rigid modes, six deformation modes with positive stiffness.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(k);
    EXPECT_LT(eig.eigenvalues()[5], 1e-10 * eig.eigenvalues()[11]);
    EXPECT_GT(eig.eigenvalues()[6], 1e-6 * eig.eigenvalues()[11]);
}

// u = eps x for a symmetric strain eps gives Hooke's law: sigma = lambda tr(eps) I + 2 mu eps.
TEST(TetElement, StressOfUniformStrainFollowsHookesLaw) {
    const TetMesh m = skewed_tet();
    const Material steel{210000, 0.3};
    const Lame lame = lame_parameters(steel);
    EXPECT_NEAR(lame.mu, 210000 / 2.6, 1e-9);
    EXPECT_NEAR(lame.lambda, 210000 * 0.3 / (1.3 * 0.4), 1e-9);
    Eigen::Matrix3d eps;
    eps << 1e-3, 2e-4, -1e-4, 2e-4, -5e-4, 3e-4, -1e-4, 3e-4, 2e-4;
    std::array<Eigen::Vector3d, 4> u;
    for (int a = 0; a < 4; ++a) u[a] = eps * m.vertices[a];
    const StressTensor s = tet_stress(tet_geometry(m, m.tets[0]), lame, u);
    const Eigen::Matrix3d expected =
        lame.lambda * eps.trace() * Eigen::Matrix3d::Identity() + 2 * lame.mu * eps;
    EXPECT_LT((s - expected).norm(), 1e-9 * expected.norm());
    // Uniaxial check: sigma_xx = E eps_xx when the lateral strains are -nu eps_xx.
    const Eigen::Matrix3d uniaxial = Eigen::Vector3d(1e-3, -3e-4, -3e-4).asDiagonal();
    for (int a = 0; a < 4; ++a) u[a] = uniaxial * m.vertices[a];
    const StressTensor su = tet_stress(tet_geometry(m, m.tets[0]), lame, u);
    EXPECT_NEAR(su(0, 0), 210.0, 1e-9);
    EXPECT_NEAR(su(1, 1), 0.0, 1e-9);
}
