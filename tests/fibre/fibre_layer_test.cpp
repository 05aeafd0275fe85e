#include "planner/fibre/fibre_layer.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;
using fibrecell::planner::testing::grid_layer;

namespace {

struct PlateInTension {
    LayerMesh layer = grid_layer(60, 20, 60, 40);
    std::vector<Eigen::Vector3d> v_e =
        std::vector<Eigen::Vector3d>(layer.triangles.size(), Eigen::Vector3d::UnitX());
    std::vector<double> sigma_e = std::vector<double>(layer.triangles.size(), 5.0);
    std::vector<std::uint8_t> defined = std::vector<std::uint8_t>(layer.triangles.size(), 1);
};

}  // namespace

TEST(FibreLayer, PlateInUniformTensionGetsStraightFibresAlongTheLoad) {
    PlateInTension t;
    const FibreLayer r = plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined);
    ASSERT_GE(r.paths.size(), 16u);
    EXPECT_EQ(r.dropped_short, 0u);
    EXPECT_GT(r.min_spacing_mm, 1.0);
    EXPECT_LE(r.min_spacing_mm, 1.25);
    for (const auto& p : r.paths) {
        EXPECT_EQ(p.role, PathRole::fibre);
        EXPECT_NEAR((p.points.back() - p.points.front()).norm(), 60.0, 1e-9);  // end to end
        for (const auto& q : p.points) EXPECT_NEAR(q.y(), p.points.front().y(), 1e-9);
    }
    EXPECT_TRUE(r.warnings.empty());
}

TEST(FibreLayer, PathsShorterThanTheCutterDistanceAreDroppedWithAWarning) {
    PlateInTension t;
    const FibreLayer r =
        plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined, {.cutter_distance_mm = 61});
    EXPECT_TRUE(r.paths.empty());
    EXPECT_GE(r.dropped_short, 16u);
    ASSERT_EQ(r.warnings.size(), 1u);
}

TEST(FibreLayer, NoTensionGivesNoFibresAndAWarning) {
    PlateInTension t;
    std::fill(t.sigma_e.begin(), t.sigma_e.end(), 1e-5);  // rule 3 everywhere
    const FibreLayer r = plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined,
                                          {.field = {.p = 1.0}, .spacing_mm = 1.0});
    EXPECT_TRUE(r.paths.empty());
    EXPECT_EQ(r.warnings.size(), 1u);
}
