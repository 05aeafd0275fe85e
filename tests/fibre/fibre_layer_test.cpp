#include "planner/fibre/fibre_layer.hpp"

#include "layer_test_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace fibrecell::planner;
using fibrecell::planner::layer_test::grid_layer;

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
    const FibreLayer r = plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined, {}, {});
    // Straight runs from end to end along the load, stopping W/2 short of the plate's ends so
    // the ribbon stays on the part; Step 4 joins neighbouring runs' ends (less than 2W apart)
    // there, so the runs make up serpentines.
    // W/2 in from each end, the ribbon inside the plate (and a few um for the offset's arcs).
    const auto at_an_end = [](double x) {
        return (x >= 0.5 && x < 0.51) || (x <= 59.5 && x > 59.49);
    };
    std::set<double> run_y;
    for (const auto& p : r.paths) {
        EXPECT_EQ(p.role, PathRole::fibre);
        EXPECT_FALSE(p.closed);
        for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
            const Eigen::Vector2d a = p.points[i], b = p.points[i + 1];
            if (std::abs(a.y() - b.y()) < 1e-4) {
                run_y.insert(std::round(a.y() * 1e4) / 1e4);
                continue;
            }
            EXPECT_TRUE(at_an_end(a.x()) && at_an_end(b.x()))
                << a.transpose() << " -> " << b.transpose();
            EXPECT_LT((b - a).norm(), 2.0);
        }
        EXPECT_TRUE(at_an_end(p.points.front().x()));
    }
    ASSERT_GE(run_y.size(), 16u);
    for (auto it = std::next(run_y.begin()); it != run_y.end(); ++it) {
        EXPECT_GE(*it - *std::prev(it), 1.0 - 1e-4);
        EXPECT_LE(*it - *std::prev(it), 1.25);
    }
    EXPECT_LT(r.paths.size(), run_y.size() / 2) << "most runs are joined";
    EXPECT_EQ(r.joins, run_y.size() - r.paths.size());
    EXPECT_EQ(r.dropped_short, 0u);
    EXPECT_TRUE(r.warnings.empty());
}

TEST(FibreLayer, BoundaryRingsFollowTheChosenEdgeAndCutEndsAreLinkedAlongIt) {
    PlateInTension t;
    // The outline edges along x = 0 (grid vertex i + 61 j).
    std::vector<std::array<int, 2>> left_edge;
    for (int j = 0; j < 40; ++j) left_edge.push_back({61 * j, 61 * (j + 1)});
    const FibreLayer r = plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined, left_edge,
                                          {.cutter_distance_mm = 10});
    int rings = 0;
    for (const auto& p : r.paths) {
        if (p.role == PathRole::fibre_boundary) {
            ++rings;
            for (const auto& q : p.points) EXPECT_NEAR(q.x(), 1.5, 0.1);  // d = 1.5W
            continue;
        }
        for (const auto& q : p.points) EXPECT_GE(q.x(), 2.5 - 0.1);  // cut back to d = 2.5W
    }
    EXPECT_EQ(rings, 1);
    // The spacing rule holds between different paths, rings included.
    EXPECT_GE(r.min_spacing_mm, 1.0 - 1e-9);
    EXPECT_GT(r.joins, 10u);
}

TEST(FibreLayer, PathsShorterThanTheCutterDistanceAreDroppedWithAWarning) {
    PlateInTension t;
    const FibreLayer r =
        plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined, {}, {.cutter_distance_mm = 2000});
    EXPECT_TRUE(r.paths.empty());  // the serpentines are about 1.1 m each
    EXPECT_GE(r.dropped_short, 1u);
    ASSERT_EQ(r.warnings.size(), 1u);
}

TEST(FibreLayer, NoTensionGivesNoFibresAndAWarning) {
    PlateInTension t;
    std::fill(t.sigma_e.begin(), t.sigma_e.end(), 1e-5);  // rule 3 everywhere
    const FibreLayer r = plan_fibre_layer(t.layer, t.v_e, t.sigma_e, t.defined, {},
                                          {.field = {.p = 1.0}, .spacing_mm = 1.0});
    EXPECT_TRUE(r.paths.empty());
    EXPECT_EQ(r.warnings.size(), 1u);
}
