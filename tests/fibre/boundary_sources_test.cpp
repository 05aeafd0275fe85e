// Which outline edges of a sliced layer lie on the boundary faces a region selects.
#include "planner/fibre/boundary_sources.hpp"

#include "planner/layers/slice.hpp"
#include "planner/mesh/region.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;

TEST(BoundarySources, OnlyTheOutlineCutFromTheChosenFaceIsSelected) {
    // A 20 x 10 x 4 mm box; the region selects its x = 0 face.
    VolumeModel model;
    model.mesh = structured_tet_mesh({.size = {20, 10, 4}, .cells = {10, 5, 4}});
    const auto boundary = boundary_triangles(model.mesh);
    const Region left{"left", BoxRegion{{-0.1, -1, -1}, {0.1, 11, 5}}};
    const SelectedFaces faces = selected_faces(model.mesh, select_triangles(model, boundary, left));
    const LayerMesh layer = slice_tet_mesh(model.mesh, 1.3);
    const std::vector<std::array<int, 2>> edges = selected_outline_edges(layer, faces);
    int on_left = 0;
    for (const auto& v : layer.vertices) on_left += std::abs(v.x()) < 1e-9;
    ASSERT_GT(on_left, 5);
    // The x = 0 side of the section is one chain of outline edges through every vertex on it.
    EXPECT_EQ(static_cast<int>(edges.size()), on_left - 1);
    for (const auto& [a, b] : edges) {
        EXPECT_NEAR(layer.vertices[a].x(), 0.0, 1e-9);
        EXPECT_NEAR(layer.vertices[b].x(), 0.0, 1e-9);
    }
    EXPECT_TRUE(selected_outline_edges(layer, {}).empty());
}
