// The reinforced material against closed forms: a bar with straight fibre along the load follows
// the rule of mixtures exactly, across it the matrix alone; the smeared stiffness turned by 90
// degrees gives the transverse result (Sherman-Morrison on the isotropic compliance).

#include "planner/fea/linear_elastic.hpp"
#include "planner/fea/tet_element.hpp"
#include "planner/mechanics/reinforced_material.hpp"
#include "planner/mechanics/stiffness_prediction.hpp"

#include "../fea/fea_test_meshes.hpp"

#include <gtest/gtest.h>
#include <Eigen/LU>

#include <cmath>
#include <numbers>

using namespace fibrecell::planner;
using namespace fibrecell::planner::fea_test;

namespace {

constexpr double kTol = 1e-9;
constexpr double kLength = 100, kSide = 10;

// m = (tx^2, ty^2, tz^2, ty tz, tx tz, tx ty), written here from the definition.
Eigen::Matrix<double, 6, 1> voigt_m(const Eigen::Vector3d& t) {
    Eigen::Matrix<double, 6, 1> m;
    m << t.x() * t.x(), t.y() * t.y(), t.z() * t.z(), t.y() * t.z(), t.x() * t.z(), t.x() * t.y();
    return m;
}

// Every tet holds ribbon filling `ribbon_fraction` of it, all along `t`.
FibreContent uniform_fibre(const TetMesh& mesh, const FibreMaterial& f, double ribbon_fraction,
                           const Eigen::Vector3d& t) {
    FibreContent c;
    for (const Tet& tet : mesh.tets) {
        const double volume = signed_volume(mesh, tet);
        const double length = ribbon_fraction * volume / (f.ribbon_width_mm * f.ribbon_height_mm);
        c.length_mm.push_back(length);
        c.tangents.push_back(length * t * t.transpose());
        c.orientation4.push_back(length * voigt_m(t) * voigt_m(t).transpose());
        c.placed_mm += length;
    }
    return c;
}

// A bar along x clamped at x = 0 and pulled at x = kLength with `force`.
LoadCase pulled(const TetMesh& mesh, double poisson_ratio, double force) {
    LoadCase lc;
    lc.material.poisson_ratio = poisson_ratio;
    lc.supports.push_back(
        {"clamp", vertices_where(mesh, [](const Eigen::Vector3d& p) { return p.x() < kTol; })});
    lc.loads.push_back(
        {"pull",
         boundary_where(mesh, [](const Eigen::Vector3d& p) { return p.x() > kLength - kTol; }),
         {force, 0, 0}});
    return lc;
}

struct BarCase {
    TetMesh mesh = box_mesh({kLength, kSide, kSide}, 20, 2, 2);
    FibreMaterial fibre;
    double ribbon = 0.4;  // ribbon fraction of every tet
    double force = 1000;
};

}  // namespace

// With nu = 0 the clamp does not hold back any contraction, so the bar is in uniaxial stress and
// its stiffness is E A / L with E the rule of mixtures, v_f E_f + (1 - v_f) E_m.
TEST(ReinforcedBar, AlongTheFibreItFollowsTheRuleOfMixturesExactly) {
    const BarCase b;
    const LoadCase lc = pulled(b.mesh, 0.0, b.force);
    const Reinforcement r =
        reinforcement(b.mesh, uniform_fibre(b.mesh, b.fibre, b.ribbon, Eigen::Vector3d::UnitX()),
                      b.fibre, lc.material);
    const double v_f = b.fibre.fibre_volume_fraction * b.ribbon;
    const double e_m = lc.material.youngs_modulus_mpa;
    const double e_c = v_f * b.fibre.fibre_modulus_mpa + (1 - v_f) * e_m;
    const double area = kSide * kSide;

    const StiffnessPrediction p = predict_stiffness(b.mesh, lc, r, b.fibre.fibre_modulus_mpa);
    EXPECT_NEAR(p.bare.stiffness_n_per_mm, e_m * area / kLength, 1e-9 * e_m * area / kLength);
    EXPECT_NEAR(p.reinforced.stiffness_n_per_mm, e_c * area / kLength, 1e-9 * e_c * area / kLength);
    EXPECT_NEAR(p.gain(), e_c / e_m, 1e-9);
    // The strain is F / (E_c A) everywhere: the fibre carries E_f times it, the PLA E_m times it.
    const double strain = b.force / (e_c * area);
    EXPECT_NEAR(p.reinforced.fibre_stress_peak_mpa, b.fibre.fibre_modulus_mpa * strain, 1e-6);
    EXPECT_NEAR(p.reinforced.von_mises_peak_mpa, e_m * strain, 1e-9);
    EXPECT_NEAR(p.reinforced.von_mises_p99_mpa, e_m * strain, 1e-9);
    EXPECT_NEAR(p.bare.von_mises_peak_mpa, b.force / area, 1e-9);
    EXPECT_EQ(p.bare.fibre_stress_peak_mpa, 0);
    EXPECT_NEAR(p.reinforced.displacement_mm, b.force * kLength / (e_c * area), 1e-9);
}

TEST(ReinforcedBar, AcrossTheFibreItIsTheMatrixAlone) {
    const BarCase b;
    const LoadCase lc = pulled(b.mesh, 0.0, b.force);
    for (const Eigen::Vector3d& across : {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)}) {
        const Reinforcement r = reinforcement(
            b.mesh, uniform_fibre(b.mesh, b.fibre, b.ribbon, across), b.fibre, lc.material);
        const StiffnessPrediction p = predict_stiffness(b.mesh, lc, r, b.fibre.fibre_modulus_mpa);
        EXPECT_NEAR(p.gain(), 1.0, 1e-9) << across.transpose();
        EXPECT_NEAR(p.reinforced.fibre_stress_peak_mpa, 0, 1e-9);
    }
}

// The material itself, any Poisson ratio: C = C_m + dE m m^T has, by Sherman-Morrison, the
// uniaxial compliance 1/E - (m . S e)^2 dE / (1 + dE m.S.m) along e; along the fibre that is
// 1/(E + dE), across it (turned by 90 degrees) 1/E - nu^2 dE / (E (E + dE)).
TEST(ReinforcedBar, TheOrientationTurnedBy90DegreesGivesTheTransverseCompliance) {
    const TetMesh one = box_mesh({1, 1, 1}, 1, 1, 1);
    const FibreMaterial fibre;
    const Material matrix{3500, 0.36};
    const double e = matrix.youngs_modulus_mpa, nu = matrix.poisson_ratio;
    const Lame lame = lame_parameters(matrix);
    VoigtStiffness c_m = VoigtStiffness::Zero();
    c_m.topLeftCorner<3, 3>().setConstant(lame.lambda);
    c_m.diagonal() << lame.lambda + 2 * lame.mu, lame.lambda + 2 * lame.mu,
        lame.lambda + 2 * lame.mu, lame.mu, lame.mu, lame.mu;

    const double ribbon = 0.5;
    const double d_e = fibre.fibre_volume_fraction * ribbon * (fibre.fibre_modulus_mpa - e);
    for (double deg : {0.0, 90.0}) {
        const double a = deg * std::numbers::pi / 180;
        const Eigen::Vector3d t(std::cos(a), std::sin(a), 0);
        const Reinforcement r =
            reinforcement(one, uniform_fibre(one, fibre, ribbon, t), fibre, matrix);
        for (std::size_t k = 0; k < one.tet_count(); ++k) {
            const Eigen::Matrix<double, 6, 6> s = (c_m + r.added[k]).inverse();
            const double along_x =
                deg == 0 ? 1 / (e + d_e) : 1 / e - nu * nu * d_e / (e * (e + d_e));
            const double along_y =
                deg == 0 ? 1 / e - nu * nu * d_e / (e * (e + d_e)) : 1 / (e + d_e);
            EXPECT_NEAR(s(0, 0) * e, along_x * e, 1e-12) << deg << " deg, tet " << k;
            EXPECT_NEAR(s(1, 1) * e, along_y * e, 1e-12) << deg << " deg, tet " << k;
            EXPECT_NEAR(r.fibre_fraction[k], fibre.fibre_volume_fraction * ribbon, 1e-12);
            EXPECT_NEAR(std::abs(r.direction[k].dot(t)), 1.0, 1e-12);
        }
    }
}

TEST(ReinforcedBar, OverfilledTetsAreCappedAndCounted) {
    const BarCase b;
    const Material matrix;
    const Reinforcement r = reinforcement(
        b.mesh, uniform_fibre(b.mesh, b.fibre, 2.0, Eigen::Vector3d::UnitX()), b.fibre, matrix);
    EXPECT_EQ(r.saturated_tets, static_cast<int>(b.mesh.tet_count()));
    EXPECT_EQ(r.reinforced_tets, static_cast<int>(b.mesh.tet_count()));
    for (double v : r.fibre_fraction) EXPECT_NEAR(v, b.fibre.fibre_volume_fraction, 1e-12);
}

TEST(ReinforcedBar, BadFibreParametersAreRefusedByName) {
    const BarCase b;
    const FibreContent c = uniform_fibre(b.mesh, b.fibre, 0.1, Eigen::Vector3d::UnitX());
    FibreMaterial f;
    f.fibre_volume_fraction = 1.5;
    EXPECT_THROW(
        {
            try {
                reinforcement(b.mesh, c, f, Material{});
            } catch (const std::invalid_argument& e) {
                EXPECT_NE(std::string(e.what()).find("fibre volume fraction"), std::string::npos);
                throw;
            }
        },
        std::invalid_argument);
    f = {};
    f.fibre_modulus_mpa = 1000;  // below PLA's
    EXPECT_THROW(reinforcement(b.mesh, c, f, Material{}), std::invalid_argument);
}
