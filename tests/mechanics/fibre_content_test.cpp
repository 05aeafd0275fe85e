// Fibre located in the model's tets from a layer's paths: lengths add up to the path, each tet's
// orientation tensor is the path's direction in the model frame, wherever the part was placed.

#include "planner/mechanics/fibre_content.hpp"
#include "planner/layers/placement.hpp"
#include "planner/layers/slice.hpp"

#include "../fea/fea_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace fibrecell::planner;
using namespace fibrecell::planner::fea_test;

namespace {

struct PlacedBox {
    TetMesh model = box_mesh({40, 20, 4}, 10, 5, 2);
    Placement placement;
    std::vector<ToolpathLayer> layers;
    std::vector<LayerMesh> sections;

    explicit PlacedBox(double rotate_z_deg) {
        PlacementSpec spec;
        spec.rotate_deg = {0, 0, rotate_z_deg};
        placement = placement_for(model, spec);
        const TetMesh placed = place_mesh(model, placement);
        sections.push_back(slice_tet_mesh(placed, 1.3));  // a PLA layer: its paths do not count
        sections.push_back(slice_tet_mesh(placed, 2.7));
        layers.push_back({0, 1.3, Head::pla, 0.8, {}});
        layers.push_back({1, 2.7, Head::ccf, 0.05, {}});
    }
    // A point of the model frame's xy at the layer, in the bed frame's xy.
    Eigen::Vector2d bed(double x, double y) const { return placement.apply({x, y, 0}).head<2>(); }
};

double total(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
}

}  // namespace

TEST(FibreContent, AStraightPathIsLocatedWholeAlongItsDirection) {
    for (double deg : {0.0, 90.0, 30.0}) {
        PlacedBox box(deg);
        // Along the model's x, 5 mm in from each end; a PLA path on the PLA layer is ignored.
        box.layers[1].paths.push_back(
            {PathRole::fibre, false, {box.bed(5, 10.3), box.bed(35, 10.3)}});
        box.layers[0].paths.push_back({PathRole::infill, false, {box.bed(5, 5), box.bed(35, 5)}});
        const FibreContent c = fibre_content(box.model, box.placement, box.layers, box.sections);
        EXPECT_NEAR(c.placed_mm, 30.0, 1e-9) << deg;
        EXPECT_NEAR(c.unplaced_mm, 0.0, 1e-12) << deg;
        EXPECT_NEAR(total(c.length_mm), 30.0, 1e-9) << deg;
        int holding = 0;
        for (std::size_t t = 0; t < box.model.tet_count(); ++t) {
            if (c.length_mm[t] == 0) continue;
            ++holding;
            const Eigen::Matrix3d a = c.tangents[t] / c.length_mm[t];
            EXPECT_NEAR(a(0, 0), 1.0, 1e-9) << deg << " deg, tet " << t;
            EXPECT_NEAR(a.norm(), 1.0, 1e-9);
            EXPECT_NEAR(c.orientation4[t](0, 0) / c.length_mm[t], 1.0, 1e-9);
            EXPECT_NEAR(c.orientation4[t].norm() / c.length_mm[t], 1.0, 1e-9);
            // Only tets the layer's plane cuts hold fibre.
            const Eigen::Vector3d centre = centroid(box.model, box.model.tets[t]);
            EXPECT_LT(std::abs(centre.z() - 2.7), 2.0);
        }
        EXPECT_GT(holding, 6) << deg;  // it crosses 6 cells of 4 mm, several tets each
    }
}

TEST(FibreContent, ClosedPathsCountTheirClosingEdgeAndOffPartPiecesAreUnplaced) {
    PlacedBox box(0);
    const Eigen::Vector2d a = box.bed(10, 5), b = box.bed(30, 5), c = box.bed(30, 15),
                          d = box.bed(10, 15);
    box.layers[1].paths.push_back({PathRole::fibre_boundary, true, {a, b, c, d}});
    // 10 mm of this one lie beyond the part's end at model x = 40.
    box.layers[1].paths.push_back({PathRole::fibre, false, {box.bed(30, 12), box.bed(50, 12)}});
    const FibreContent content = fibre_content(box.model, box.placement, box.layers, box.sections);
    EXPECT_NEAR(content.placed_mm, 60.0 + 10.0, 1e-9);
    EXPECT_NEAR(content.unplaced_mm, 10.0, 1e-9);
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (const auto& t : content.tangents) sum += t;
    EXPECT_NEAR(sum(0, 0), 20 + 20 + 10, 1e-9);  // the ring's x sides and the placed 10 mm
    EXPECT_NEAR(sum(1, 1), 20, 1e-9);
    EXPECT_NEAR(sum(0, 1), 0, 1e-9);
}

TEST(FibreContent, LayersAndSectionsMustPair) {
    PlacedBox box(0);
    box.sections.pop_back();
    EXPECT_THROW(fibre_content(box.model, box.placement, box.layers, box.sections),
                 std::invalid_argument);
}
