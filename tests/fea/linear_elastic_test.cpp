// Static FEA against closed-form solutions: a bar in tension, a cantilever, a plate with a hole.

#include "planner/fea/linear_elastic.hpp"

#include "fea_test_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

using namespace fibrecell::planner;
using namespace fibrecell::planner::fea_test;

namespace {

// A bar along x, [0, l] x [0, side] x [0, side], clamped at x = 0 and pulled at x = l.
struct Bar {
    double length = 100, side = 10;
    TetMesh mesh;
    LoadCase load_case;
};

Bar pulled_bar(double force_n, double poisson_ratio) {
    Bar b;
    b.mesh = box_mesh({b.length, b.side, b.side}, 40, 4, 4);
    b.load_case.material.poisson_ratio = poisson_ratio;
    b.load_case.supports.push_back(
        {"clamp", vertices_where(b.mesh, [](const Eigen::Vector3d& p) { return p.x() < kTol; })});
    b.load_case.loads.push_back(
        {"pull",
         boundary_where(b.mesh, [&](const Eigen::Vector3d& p) { return p.x() > b.length - kTol; }),
         {force_n, 0, 0}});
    return b;
}

}  // namespace

// With nu = 0 the clamp does not hinder any lateral contraction, so u = (F x / EA, 0, 0) is the
// exact solution; linear tets represent it exactly, so every element carries F/A.
TEST(LinearElastic, UniaxialBarWithoutPoissonIsExactEverywhere) {
    const double force = 1000;
    const Bar b = pulled_bar(force, 0.0);
    const FeaResult r = solve_linear_elastic(b.mesh, b.load_case);
    const double nominal = force / (b.side * b.side);  // 10 MPa
    ASSERT_EQ(r.stress.size(), b.mesh.tet_count());
    StressTensor uniaxial = StressTensor::Zero();
    uniaxial(0, 0) = nominal;
    for (const StressTensor& s : r.stress) EXPECT_LT((s - uniaxial).norm(), 1e-6 * nominal);
    const double stretch =
        force * b.length / (b.load_case.material.youngs_modulus_mpa * b.side * b.side);
    for (std::size_t v = 0; v < b.mesh.vertex_count(); ++v) {
        if (b.mesh.vertices[v].x() > b.length - kTol) {
            EXPECT_NEAR(r.displacement[v].x(), stretch, 1e-9);
        }
    }
    EXPECT_NEAR(r.compliance_nmm, force * stretch, 1e-9 * force * stretch);  // f . u
}

// With PLA's nu the fully clamped end (all three displacements fixed) holds the section at its
// full size, which disturbs the stress near it (Saint-Venant); one bar width away the state is
// uniaxial again, and the loaded end carries a uniform traction, so it is undisturbed.
TEST(LinearElastic, UniaxialBarAwayFromClampCarriesForceOverArea) {
    const double force = 1000;
    const Bar b = pulled_bar(force, 0.36);
    const FeaResult r = solve_linear_elastic(b.mesh, b.load_case);
    const double nominal = force / (b.side * b.side);
    int checked = 0;
    for (std::size_t t = 0; t < b.mesh.tet_count(); ++t) {
        if (centroid(b.mesh, b.mesh.tets[t]).x() < 2 * b.side) continue;
        EXPECT_NEAR(r.stress[t](0, 0), nominal, 0.01 * nominal) << "tet " << t;
        ++checked;
    }
    EXPECT_GT(checked, 0);
}

TEST(LinearElastic, ReactionsBalanceTheAppliedLoad) {
    const Eigen::Vector3d force(1000, -200, 50);
    Bar b = pulled_bar(0, 0.36);
    b.load_case.loads[0].total_force_n = force;
    const FeaResult r = solve_linear_elastic(b.mesh, b.load_case);
    const Eigen::Vector3d total = sum(r.reaction);
    EXPECT_LT((total + force).norm(), 1e-6 * force.norm()) << total.transpose();
    // Reactions only where the bar is held.
    for (std::size_t v = 0; v < b.mesh.vertex_count(); ++v) {
        if (b.mesh.vertices[v].x() > kTol) {
            EXPECT_EQ(r.reaction[v], Eigen::Vector3d::Zero());
        }
    }
    EXPECT_EQ(r.dof_count, 3 * (b.mesh.vertex_count() - 25));  // 5 x 5 clamped vertices
}

// Tip load P on a cantilever L = 100, 5 x 10 mm section (bending about the width). Timoshenko:
// delta = P L^3 / (3 E I) + P L / (k G A), k = 5/6 (the shear term is 0.8 % here). Linear tets
// are too stiff in bending, so the mesh has 20 cells through the depth; it lands ~4 % low.
TEST(LinearElastic, CantileverTipDeflectionMatchesTimoshenko) {
    const double l = 100, b = 5, h = 10, p = 10;
    const TetMesh mesh = box_mesh({l, b, h}, 100, 2, 20);
    LoadCase lc;
    lc.supports.push_back(
        {"wall", vertices_where(mesh, [](const Eigen::Vector3d& q) { return q.x() < kTol; })});
    lc.loads.push_back(
        {"tip",
         boundary_where(mesh, [&](const Eigen::Vector3d& q) { return q.x() > l - kTol; }),
         {0, 0, -p}});
    const FeaResult r = solve_linear_elastic(mesh, lc);

    double tip = 0;  // mean vertical displacement of the end face [mm]
    int n = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        if (mesh.vertices[v].x() > l - kTol) tip += r.displacement[v].z(), ++n;
    tip /= n;
    const double e = lc.material.youngs_modulus_mpa;
    const double g = e / (2 * (1 + lc.material.poisson_ratio));
    const double inertia = b * h * h * h / 12;
    const double expected = p * l * l * l / (3 * e * inertia) + p * l / (5.0 / 6.0 * g * b * h);
    EXPECT_NEAR(-tip, expected, 0.05 * expected);
}

// Kirsch: a hole in an infinite plate under tension S raises the hoop stress at the hole's
// flanks to 3 S. The plate here is d/W = 0.1, so compare with Heywood's finite-width factor on
// the gross stress, Kt = (2 + (1 - d/W)^3) / (1 - d/W) = 3.03. The plate is thin (t/a = 0.2:
// near plane stress) and long (clamp 150 mm from the hole). Constant-strain tets and the
// element nearest the flank put the peak a few per cent high; allow 10 %.
TEST(LinearElastic, PlateWithHoleReachesKirschConcentration) {
    const HolePlate plate;
    const TetMesh mesh = hole_plate_mesh(plate);
    const double half_length = plate.length() / 2;
    const double nominal = 10;  // gross section stress S [MPa]
    LoadCase lc;
    lc.supports.push_back({"clamp", vertices_where(mesh, [&](const Eigen::Vector3d& q) {
                               return q.x() < -half_length + kTol;
                           })});
    lc.loads.push_back(
        {"pull",
         boundary_where(mesh, [&](const Eigen::Vector3d& q) { return q.x() > half_length - kTol; }),
         {nominal * plate.width * plate.thickness, 0, 0}});
    const FeaResult r = solve_linear_elastic(mesh, lc);

    double peak = 0;
    Eigen::Vector3d where = Eigen::Vector3d::Zero();
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        if (r.stress[t](0, 0) > peak)
            peak = r.stress[t](0, 0), where = centroid(mesh, mesh.tets[t]);
    const double d_over_w = 2 * plate.hole_radius / plate.width;
    const double heywood = (2 + std::pow(1 - d_over_w, 3)) / (1 - d_over_w);
    EXPECT_NEAR(peak / nominal, heywood, 0.10 * heywood);
    // At the flank of the hole: x ~ 0, |y| ~ a.
    EXPECT_LT(std::abs(where.x()), 0.5);
    EXPECT_NEAR(std::abs(where.y()), plate.hole_radius, 0.5);
}

TEST(LinearElastic, BothSolversAgree) {
    Bar b = pulled_bar(0, 0.36);
    b.load_case.loads[0].total_force_n = {300, 40, -70};
    FeaOptions cholmod;
    cholmod.solver = LinearSolver::cholmod_supernodal;
    FeaOptions eigen;
    eigen.solver = LinearSolver::eigen_simplicial_ldlt;
    const FeaResult a = solve_linear_elastic(b.mesh, b.load_case, cholmod);
    const FeaResult c = solve_linear_elastic(b.mesh, b.load_case, eigen);
    EXPECT_EQ(a.solver, "cholmod_supernodal");
    EXPECT_EQ(c.solver, "eigen_simplicial_ldlt");
    double scale = 0;
    for (const auto& u : a.displacement) scale = std::max(scale, u.norm());
    for (std::size_t v = 0; v < b.mesh.vertex_count(); ++v)
        EXPECT_LT((a.displacement[v] - c.displacement[v]).norm(), 1e-9 * scale);
}

// Vertices no tet uses (Gmsh keeps geometry points, say) neither move nor make K singular.
TEST(LinearElastic, UnusedVerticesStayAtRest) {
    Bar b = pulled_bar(1000, 0.36);
    b.mesh.vertices.emplace_back(500, 500, 500);
    const FeaResult r = solve_linear_elastic(b.mesh, b.load_case);
    EXPECT_EQ(r.displacement.back(), Eigen::Vector3d::Zero());
    EXPECT_EQ(r.reaction.back(), Eigen::Vector3d::Zero());
}

TEST(LinearElastic, ReportsProgressAndStopsWhenCancelled) {
    const Bar b = pulled_bar(1000, 0.36);
    std::vector<double> fractions;
    StepControl control;
    control.progress = [&](std::string_view stage, double f) {
        EXPECT_EQ(stage, "fea");
        fractions.push_back(f);
    };
    solve_linear_elastic(b.mesh, b.load_case, {}, control);
    ASSERT_GE(fractions.size(), 4u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));

    CancelToken cancel;
    control.cancel = &cancel;
    control.progress = [&](std::string_view, double f) {
        if (f > 0.1) cancel.cancel();  // after the assembly has started
    };
    EXPECT_THROW(solve_linear_elastic(b.mesh, b.load_case, {}, control), Cancelled);
}
