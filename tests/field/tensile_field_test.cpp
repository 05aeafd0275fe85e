#include "planner/field/tensile_field.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <random>

using namespace fibrecell::planner;

namespace {

StressTensor diag(double a, double b, double c) {
    return Eigen::Vector3d(a, b, c).asDiagonal();
}

// |dot| of unit vectors: directions are only defined up to sign.
double alignment(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::abs(a.dot(b));
}

}  // namespace

TEST(PrincipalStress, SortedByAbsoluteValueWithMatchingDirections) {
    const PrincipalStress p = principal_stress(diag(1.0, -5.0, 2.0));
    EXPECT_NEAR(p.values[0], -5.0, 1e-12);
    EXPECT_NEAR(p.values[1], 2.0, 1e-12);
    EXPECT_NEAR(p.values[2], 1.0, 1e-12);
    EXPECT_NEAR(alignment(p.directions.col(0), Eigen::Vector3d::UnitY()), 1.0, 1e-12);
    EXPECT_NEAR(alignment(p.directions.col(1), Eigen::Vector3d::UnitZ()), 1.0, 1e-12);
    EXPECT_NEAR(alignment(p.directions.col(2), Eigen::Vector3d::UnitX()), 1.0, 1e-12);
}

TEST(PrincipalStress, ClosedFormAgreesWithIterativeSolver) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-100.0, 100.0);
    for (int i = 0; i < 500; ++i) {
        StressTensor s;
        s << u(rng), u(rng), u(rng), 0, u(rng), u(rng), 0, 0, u(rng);
        s = s.selfadjointView<Eigen::Upper>();
        const PrincipalStress p = principal_stress(s);
        // Reconstruct the tensor from the decomposition: an independent check of values and
        // directions together.
        const StressTensor back = p.directions * p.values.asDiagonal() * p.directions.transpose();
        EXPECT_LT((back - s).norm(), 1e-9 * s.norm());
        EXPECT_GE(std::abs(p.values[0]), std::abs(p.values[1]));
        EXPECT_GE(std::abs(p.values[1]), std::abs(p.values[2]));
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ref(s);
        EXPECT_NEAR(p.values.cwiseAbs().maxCoeff(), ref.eigenvalues().cwiseAbs().maxCoeff(), 1e-9);
    }
}

TEST(TensileField, RuleOneTension) {
    const auto f = tensile_field({diag(10.0, 1.0, -2.0)});
    EXPECT_EQ(f.rule[0], TensileRule::first_principal);
    EXPECT_DOUBLE_EQ(f.sigma_e[0], 10.0);
    EXPECT_NEAR(alignment(f.v_e[0], Eigen::Vector3d::UnitX()), 1.0, 1e-12);
}

TEST(TensileField, RuleTwoCompressionDominatedButTensionUseful) {
    // sigma_1 = -4 (y), sigma_2 = 2 (z): |-4 / 2| = 2 < mu = 3.
    const auto f = tensile_field({diag(0.5, -4.0, 2.0)});
    EXPECT_EQ(f.rule[0], TensileRule::second_principal);
    EXPECT_DOUBLE_EQ(f.sigma_e[0], 2.0);
    EXPECT_NEAR(alignment(f.v_e[0], Eigen::Vector3d::UnitZ()), 1.0, 1e-12);
}

TEST(TensileField, RuleThreeWhenTensionTooSmallOrAbsent) {
    // |-7 / 2| = 3.5 >= mu; exactly mu is not "< mu" either; pure compression; zero stress.
    const auto f = tensile_field(
        {diag(-7.0, 2.0, 0.0), diag(-6.0, 2.0, 0.0), diag(-1.0, -2.0, -3.0), diag(0.0, 0.0, 0.0)});
    for (int e = 0; e < 4; ++e) {
        EXPECT_EQ(f.rule[e], TensileRule::no_tension) << "element " << e;
        EXPECT_DOUBLE_EQ(f.sigma_e[e], 1e-5);
        EXPECT_NEAR(f.v_e[e].norm(), 1.0, 1e-12);
    }
    EXPECT_NEAR(alignment(f.v_e[0], Eigen::Vector3d::UnitX()), 1.0, 1e-12);  // tau_1
    EXPECT_NEAR(alignment(f.v_e[2], Eigen::Vector3d::UnitZ()), 1.0, 1e-12);
}

TEST(TensileField, MuIsConfigurable) {
    const auto f = tensile_field({diag(-7.0, 2.0, 0.0)}, {.mu = 4.0});
    EXPECT_EQ(f.rule[0], TensileRule::second_principal);
}
