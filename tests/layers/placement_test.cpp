#include "planner/layers/placement.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <stdexcept>

using namespace fibrecell::planner;

namespace {

TetMesh box(const Eigen::Vector3d& size) {
    StructuredMeshOptions o;
    o.size = size;
    o.cells = {2, 2, 2};
    return structured_tet_mesh(o);
}

void expect_on_bed_at(const TetMesh& placed, const Eigen::Vector2d& centre) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (const auto& p : placed.vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    EXPECT_NEAR(lo.z(), 0.0, 1e-12);
    EXPECT_NEAR(0.5 * (lo.x() + hi.x()), centre.x(), 1e-9);
    EXPECT_NEAR(0.5 * (lo.y() + hi.y()), centre.y(), 1e-9);
    for (const Tet& t : placed.tets) EXPECT_GT(signed_volume(placed, t), 0.0);
}

}  // namespace

TEST(Placement, QuarterTurnAboutXStandsTheBoxOnItsSide) {
    const TetMesh mesh = box({10, 20, 30});
    PlacementSpec spec;
    spec.rotate_deg = {90, 0, 0};  // (x, y, z) -> (x, -z, y)
    const Placement placement = placement_for(mesh, spec);
    const TetMesh placed = place_mesh(mesh, placement);
    expect_on_bed_at(placed, spec.position_mm);
    EXPECT_DOUBLE_EQ(part_height(placed), 20.0);
    // Exact quarter turns keep vertex layers exactly flat.
    EXPECT_EQ(placement.rotation(2, 1), 1.0);
    EXPECT_EQ(placement.rotation(2, 2), 0.0);
    const std::vector<Eigen::Vector3d> v = {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 2)};
    const auto turned = rotate_vectors(v, placement);
    EXPECT_TRUE(turned[0].isApprox(Eigen::Vector3d(0, 0, 1)));
    EXPECT_TRUE(turned[1].isApprox(Eigen::Vector3d(0, -2, 0)));
}

TEST(Placement, RotatesAboutXThenYThenZ) {
    const TetMesh mesh = box({3, 5, 7});
    PlacementSpec spec;
    spec.rotate_deg = {30, 45, -60};
    spec.position_mm = {10, -20};
    const Placement placement = placement_for(mesh, spec);
    const double rad = M_PI / 180;
    const Eigen::Matrix3d expected = (Eigen::AngleAxisd(-60 * rad, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(45 * rad, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(30 * rad, Eigen::Vector3d::UnitX()))
                                         .toRotationMatrix();
    EXPECT_TRUE(placement.rotation.isApprox(expected, 1e-14));
    expect_on_bed_at(place_mesh(mesh, placement), spec.position_mm);
}

TEST(Placement, RejectsEmptyMeshAndNonFiniteSpec) {
    EXPECT_THROW(placement_for(TetMesh{}, PlacementSpec{}), std::invalid_argument);
    PlacementSpec spec;
    spec.rotate_deg.x() = NAN;
    EXPECT_THROW(placement_for(box({1, 1, 1}), spec), std::invalid_argument);
    spec = {};
    spec.position_mm.y() = INFINITY;
    EXPECT_THROW(placement_for(box({1, 1, 1}), spec), std::invalid_argument);
    EXPECT_THROW(part_height(TetMesh{}), std::invalid_argument);
}
