// The reference parts (bunnyhead, YogaNew) placed on the bed and cut at every PLA layer: real
// meshes whose outlines change with height, with islands and holes. The parts come from the shared
// folder beside the repository; the tests skip when it is missing.

#include "planner/io/read_model.hpp"
#include "planner/layers/layer_schedule.hpp"
#include "planner/layers/outline.hpp"
#include "planner/layers/placement.hpp"
#include "planner/layers/slice.hpp"

#include "layer_checks.hpp"
#include "tests/support/shared_data.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

using namespace fibrecell::planner;
using namespace fibrecell::planner::test;

namespace {

class ReferenceLayers : public ::testing::TestWithParam<std::string> {};

// Each part is read once for all tests (reading dominates under the sanitizers).
const TetMesh& reference_mesh(const std::string& name) {
    static std::map<std::string, TetMesh> cache;
    auto it = cache.find(name);
    if (it == cache.end()) {
        const std::string base = fibrecell::test::reference_fea_stem(name);
        it = cache.emplace(name, read_volume_model(base + ".tet").mesh).first;
    }
    return it->second;
}

double mesh_volume(const TetMesh& mesh) {
    double sum = 0;
    for (const Tet& t : mesh.tets) sum += signed_volume(mesh, t);
    return sum;
}

}  // namespace

TEST_P(ReferenceLayers, EveryPlaLayerIsACleanSectionAndTheLayersAddUpToTheVolume) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA(GetParam());
    const TetMesh& mesh = reference_mesh(GetParam());
    const TetMesh placed = place_mesh(mesh, placement_for(mesh, PlacementSpec{}));
    const double height = part_height(placed);

    LayerScheduleSpec spec;
    spec.ccf_on_all = false;  // PLA layers only: they tile [0, H] exactly
    const auto schedule = layer_schedule(height, spec);
    std::vector<double> heights;
    for (const auto& layer : schedule) heights.push_back(layer.slice_z);
    const auto layers = slice_layers(placed, heights);
    const SliceIndex index = build_slice_index(placed);

    double integrated = 0;
    std::size_t loop_count_min = SIZE_MAX, loop_count_max = 0;
    for (const LayerMesh& layer : layers) {
        SCOPED_TRACE("z = " + std::to_string(layer.z));
        ASSERT_FALSE(layer.triangles.empty());
        EXPECT_GT(min_triangle_area(layer), 0.0);
        EXPECT_TRUE(edges_conform(layer));
        for (int t : layer.triangle_tet) {
            EXPECT_LE(index.tet_z_min[t], layer.z);
            EXPECT_GE(index.tet_z_max[t], layer.z);
        }
        const double area = area_sum(layer);
        const LayerOutline outline = layer_outline(layer);
        double loop_area = 0;
        for (const auto& loop : outline.loops) {
            EXPECT_GE(loop.size(), 3u);
            EXPECT_FALSE(loop_has_repeated_point(loop));
            loop_area += signed_area(loop);
        }
        EXPECT_NEAR(loop_area, area, 1e-6 * area);
        loop_count_min = std::min(loop_count_min, outline.loops.size());
        loop_count_max = std::max(loop_count_max, outline.loops.size());
        integrated += area * (height / static_cast<double>(layers.size()));
    }
    const double volume = mesh_volume(placed);
    EXPECT_NEAR(integrated, volume, 0.03 * volume);
    EXPECT_GT(loop_count_max, loop_count_min) << "outline topology should change with height";
}

TEST_P(ReferenceLayers, PlanesExactlyThroughMeshVerticesGiveCleanSections) {
    FIBRECELL_SKIP_WITHOUT_REFERENCE_FEA(GetParam());
    const TetMesh& mesh = reference_mesh(GetParam());
    const SliceIndex index = build_slice_index(mesh);
    // Heights of vertices spread over the part: the plane holds at least one mesh vertex.
    for (std::size_t v = 17; v < mesh.vertices.size(); v += mesh.vertices.size() / 12) {
        const double z = mesh.vertices[v].z();
        SCOPED_TRACE("vertex " + std::to_string(v) + ", z = " + std::to_string(z));
        const LayerMesh layer = slice_tet_mesh(mesh, index, z);
        if (layer.triangles.empty()) continue;  // the part's lowest vertex
        EXPECT_GT(min_triangle_area(layer), 0.0);
        EXPECT_TRUE(edges_conform(layer));
        EXPECT_TRUE(vertices_distinct(layer));
        const double area = area_sum(layer);
        double loop_area = 0;
        for (const auto& loop : layer_outline(layer).loops) {
            EXPECT_FALSE(loop_has_repeated_point(loop));
            loop_area += signed_area(loop);
        }
        EXPECT_NEAR(loop_area, area, 1e-6 * area);
        // The same section as just below the plane.
        EXPECT_NEAR(area_sum(slice_tet_mesh(mesh, index, z - 1e-7)), area, 1e-4 * area);
    }
}

INSTANTIATE_TEST_SUITE_P(Parts, ReferenceLayers, ::testing::Values("bunnyhead", "YogaNew"));
