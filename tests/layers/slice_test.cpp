#include "planner/layers/slice.hpp"
#include "planner/layers/outline.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include "layer_checks.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace fibrecell::planner;
using namespace fibrecell::planner::test;

namespace {

// 4 x 3 x 5 mm box of 1 mm cells: vertex layers at every whole z.
TetMesh box() {
    StructuredMeshOptions o;
    o.size = {4, 3, 5};
    o.cells = {4, 3, 5};
    return structured_tet_mesh(o);
}

// Every triangle's tet spans the plane (up to the snap tolerance), and the section is one clean
// piece of area w * h.
void expect_full_section(const TetMesh& mesh, const LayerMesh& layer, double area) {
    ASSERT_FALSE(layer.triangles.empty());
    ASSERT_EQ(layer.triangle_tet.size(), layer.triangles.size());
    EXPECT_NEAR(area_sum(layer), area, 1e-9);
    EXPECT_GT(min_triangle_area(layer), 0.0);
    EXPECT_EQ(edge_connected_components(layer), 1);
    EXPECT_TRUE(edges_conform(layer));
    EXPECT_TRUE(vertices_distinct(layer));
    for (int t : layer.triangle_tet) {
        double lo = INFINITY, hi = -INFINITY;
        for (int v : mesh.tets[t]) {
            lo = std::min(lo, mesh.vertices[v].z());
            hi = std::max(hi, mesh.vertices[v].z());
        }
        EXPECT_LE(lo, layer.z + 1e-9);
        EXPECT_GE(hi, layer.z - 1e-9);
    }
}

void expect_rectangle_outline(const LayerMesh& layer, double w, double h) {
    const LayerOutline outline = layer_outline(layer);
    ASSERT_EQ(outline.loops.size(), 1u);
    EXPECT_NEAR(signed_area(outline.loops[0]), w * h, 1e-9);
    EXPECT_NEAR(perimeter(outline.loops[0]), 2 * (w + h), 1e-9);
    EXPECT_FALSE(loop_has_repeated_point(outline.loops[0]));
}

}  // namespace

TEST(Slice, BoxAtAnArbitraryHeight) {
    const TetMesh mesh = box();
    for (double z : {0.37, 2.5, 4.999}) {
        SCOPED_TRACE(z);
        const LayerMesh layer = slice_tet_mesh(mesh, z);
        EXPECT_EQ(layer.z, z);
        expect_full_section(mesh, layer, 12.0);
        expect_rectangle_outline(layer, 4, 3);
    }
}

TEST(Slice, BoxExactlyAtAVertexLayerUsesTheMeshVertices) {
    const TetMesh mesh = box();
    const SliceIndex index = build_slice_index(mesh);
    for (double z : {1.0, 2.0, 5.0}) {
        SCOPED_TRACE(z);
        const LayerMesh layer = slice_tet_mesh(mesh, index, z);
        expect_full_section(mesh, layer, 12.0);
        expect_rectangle_outline(layer, 4, 3);
        EXPECT_EQ(layer.vertices.size(), 5u * 4u);  // exactly the grid vertices of that layer
        // The plane is taken an infinitesimal step low: the same as just below the layer.
        const LayerMesh just_below = slice_tet_mesh(mesh, index, z - 1e-6);
        EXPECT_NEAR(area_sum(just_below), area_sum(layer), 1e-9);
    }
}

TEST(Slice, NothingAtOrOutsideTheBottomAndTop) {
    const TetMesh mesh = box();
    const SliceIndex index = build_slice_index(mesh);
    for (double z : {-1.0, 0.0, 5.0 + 1e-6, 7.0}) {
        SCOPED_TRACE(z);
        const LayerMesh layer = slice_tet_mesh(mesh, index, z);
        EXPECT_TRUE(layer.triangles.empty());
        EXPECT_TRUE(layer.vertices.empty());
        EXPECT_TRUE(layer_outline(layer).loops.empty());
    }
}

TEST(Slice, NearlyOnAVertexLayerSnapsToIt) {
    // Grid coordinates off by rounding noise still give the clean vertex-layer section.
    TetMesh mesh = box();
    for (auto& p : mesh.vertices)
        if (p.z() == 2.0) p.z() += (p.x() > 1.5 ? 1e-13 : -1e-13);
    const LayerMesh layer = slice_tet_mesh(mesh, 2.0);
    expect_full_section(mesh, layer, 12.0);
    EXPECT_EQ(layer.vertices.size(), 20u);
    expect_rectangle_outline(layer, 4, 3);
}

TEST(Slice, JitteredInteriorVerticesStillGiveAConformingSection) {
    // Irregular tets with exact vertex layers: planes through vertices in every configuration.
    StructuredMeshOptions o;
    o.size = {6, 6, 4};
    o.cells = {6, 6, 4};
    TetMesh mesh = structured_tet_mesh(o);
    int k = 0;
    for (auto& p : mesh.vertices) {
        ++k;
        const bool side_x = p.x() == 0 || p.x() == 6, side_y = p.y() == 0 || p.y() == 6;
        if (!side_x) p.x() += 0.12 * std::sin(1.7 * k);
        if (!side_y) p.y() += 0.12 * std::cos(2.3 * k);
        if (p.z() > 0 && p.z() < 4 && k % 3 == 0) p.z() += 0.12 * std::sin(0.9 * k);
    }
    for (const Tet& t : mesh.tets) ASSERT_GT(signed_volume(mesh, t), 0.0);
    const SliceIndex index = build_slice_index(mesh);
    for (double z : {0.5, 1.0, 1.25, 2.0, 2.9, 3.0, 4.0}) {
        SCOPED_TRACE(z);
        const LayerMesh layer = slice_tet_mesh(mesh, index, z);
        expect_full_section(mesh, layer, 36.0);
        expect_rectangle_outline(layer, 6, 6);
    }
}

TEST(Slice, SingleTetThroughEachVertexAndFace) {
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {2, 0, 1}, {0, 2, 1}, {1, 1, 3}};
    mesh.tets = {{0, 1, 2, 3}};
    ASSERT_GT(signed_volume(mesh, mesh.tets[0]), 0.0);
    // At z = 1 the plane holds edge 1-2; the section is the triangle below-and-on: (1, 2, p(0,3)).
    const LayerMesh at_edge = slice_tet_mesh(mesh, 1.0);
    ASSERT_EQ(at_edge.triangles.size(), 1u);
    EXPECT_GT(min_triangle_area(at_edge), 0.0);
    EXPECT_EQ(at_edge.vertices.size(), 3u);
    EXPECT_TRUE(slice_tet_mesh(mesh, 3.0).triangles.empty());  // only the apex
    EXPECT_TRUE(slice_tet_mesh(mesh, 0.0).triangles.empty());  // the plane is below the tet
    // A face in the plane, the tet below it: the face itself.
    TetMesh flat_top;
    flat_top.vertices = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0.2, 0.2, 0}};
    flat_top.tets = {{0, 2, 1, 3}};
    ASSERT_GT(signed_volume(flat_top, flat_top.tets[0]), 0.0);
    const LayerMesh face = slice_tet_mesh(flat_top, 1.0);
    ASSERT_EQ(face.triangles.size(), 1u);
    EXPECT_NEAR(area_sum(face), 0.5, 1e-15);
}

TEST(Slice, PlateWithAHoleHasAnOuterLoopAndAClockwiseHole) {
    StructuredMeshOptions o;
    o.size = {10, 10, 2};
    o.cells = {10, 10, 2};
    o.keep_cell = [](const Eigen::Vector3d& c) {
        return !(c.x() > 4 && c.x() < 6 && c.y() > 4 && c.y() < 6);
    };
    const TetMesh mesh = structured_tet_mesh(o);
    for (double z : {0.3, 1.0}) {
        SCOPED_TRACE(z);
        const LayerMesh layer = slice_tet_mesh(mesh, z);
        expect_full_section(mesh, layer, 96.0);
        const LayerOutline outline = layer_outline(layer);
        ASSERT_EQ(outline.loops.size(), 2u);
        std::vector<double> areas;
        for (const auto& loop : outline.loops) {
            areas.push_back(signed_area(loop));
            EXPECT_FALSE(loop_has_repeated_point(loop));
        }
        std::sort(areas.begin(), areas.end());
        EXPECT_NEAR(areas[0], -4.0, 1e-9);
        EXPECT_NEAR(areas[1], 100.0, 1e-9);
    }
}

TEST(Slice, TwoBlocksGiveTwoOuterLoops) {
    StructuredMeshOptions o;
    o.size = {10, 4, 3};
    o.cells = {10, 4, 3};
    o.keep_cell = [](const Eigen::Vector3d& c) { return c.x() < 3 || c.x() > 6; };
    const TetMesh mesh = structured_tet_mesh(o);
    const LayerMesh layer = slice_tet_mesh(mesh, 1.5);
    EXPECT_NEAR(area_sum(layer), 7 * 4.0, 1e-9);
    EXPECT_EQ(edge_connected_components(layer), 2);
    const LayerOutline outline = layer_outline(layer);
    ASSERT_EQ(outline.loops.size(), 2u);
    std::vector<double> areas = {signed_area(outline.loops[0]), signed_area(outline.loops[1])};
    std::sort(areas.begin(), areas.end());
    EXPECT_NEAR(areas[0], 12.0, 1e-9);
    EXPECT_NEAR(areas[1], 16.0, 1e-9);
}

TEST(Slice, IndexedAndUnindexedAgree) {
    const TetMesh mesh = box();
    const SliceIndex index = build_slice_index(mesh);
    for (double z : {0.1, 1.0, 3.3}) {
        const LayerMesh a = slice_tet_mesh(mesh, z), b = slice_tet_mesh(mesh, index, z);
        EXPECT_EQ(a.triangles, b.triangles);
        EXPECT_EQ(a.triangle_tet, b.triangle_tet);
    }
    const std::vector<double> heights = {0.5, 1.5};
    int reports = 0;
    StepControl control;
    control.progress = [&](std::string_view stage, double) { reports += stage == "slice"; };
    const auto layers = slice_layers(mesh, heights, {}, control);
    ASSERT_EQ(layers.size(), 2u);
    EXPECT_EQ(reports, 2);
    EXPECT_EQ(layers[1].z, 1.5);
}

TEST(Slice, RejectsBadInput) {
    TetMesh mesh = box();
    EXPECT_THROW(slice_tet_mesh(mesh, NAN), std::invalid_argument);
    EXPECT_THROW(slice_tet_mesh(mesh, 1.0, SliceOptions{.snap_tolerance = -1}),
                 std::invalid_argument);
    const SliceIndex index = build_slice_index(mesh);
    TetMesh fewer = mesh;
    fewer.tets.pop_back();
    EXPECT_THROW(slice_tet_mesh(fewer, index, 1.0), std::invalid_argument);
    TetMesh bad_index = mesh;
    bad_index.tets[3][2] = 100000;
    EXPECT_THROW(build_slice_index(bad_index), std::invalid_argument);
    TetMesh inverted = mesh;
    std::swap(inverted.tets[0][0], inverted.tets[0][1]);
    try {
        slice_tet_mesh(inverted, 0.5);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("tet 0"), std::string::npos) << e.what();
    }
}
