#include "planner/mesh/region.hpp"

#include "planner/mesh/structured_mesh.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace fibrecell::planner;

namespace {

VolumeModel cube_model() {
    VolumeModel m;
    m.mesh = structured_tet_mesh({.size = {2, 2, 2}, .cells = {2, 2, 2}});
    return m;
}

int count(const std::vector<char>& inside) {
    return static_cast<int>(std::count(inside.begin(), inside.end(), 1));
}

}  // namespace

TEST(Region, BoxIsInclusive) {
    const VolumeModel m = cube_model();
    const Region face{"x0", BoxRegion{{0, 0, 0}, {0, 2, 2}}};
    EXPECT_EQ(count(vertices_inside(m, face)), 9);  // the 3 x 3 vertices of the x = 0 face
}

TEST(Region, CylinderSelectsAShellAndFacingSelectsHalfOfIt) {
    VolumeModel m;
    for (int i = 0; i < 8; ++i) {
        const double a = i * M_PI / 4;
        m.mesh.vertices.emplace_back(5 * std::cos(a), 5 * std::sin(a), 1.0);  // on the shell
    }
    m.mesh.vertices.emplace_back(0, 0, 1);  // on the axis
    m.mesh.vertices.emplace_back(8, 0, 1);  // outside
    CylinderRegion c{{0, 0, 0}, {0, 0, 1}, 5.0, 0.01};
    EXPECT_EQ(count(vertices_inside(m, {"ring", c})), 8);
    c.facing = {1, 0, 0};
    // cos(a) >= 0 for a = 0, 45, 90, 270, 315 degrees (90 and 270 lie on the dividing plane).
    EXPECT_EQ(count(vertices_inside(m, {"half", c})), 5);
}

TEST(Region, TriangleNeedsAllThreeVerticesInside) {
    const VolumeModel m = cube_model();
    const auto boundary = boundary_triangles(m.mesh);
    // The x = 0 face plus a sliver: triangles of the y = 0 face touch it with 2 vertices only.
    const auto tris = select_triangles(m, boundary, {"x0", BoxRegion{{0, 0, 0}, {0, 2, 2}}});
    EXPECT_EQ(tris.size(), 8u);  // 2 x 2 squares, 2 triangles each
    for (const auto& t : tris)
        for (int v : t.v) EXPECT_EQ(m.mesh.vertices[v].x(), 0.0);
    EXPECT_EQ(triangle_vertices(tris).size(), 9u);
}

TEST(Region, GroupsComeFromTheMeshFileAndMissingOnesAreNamed) {
    VolumeModel m = cube_model();
    m.vertex_groups["fixed"] = {0, 1, 2};
    EXPECT_EQ(count(vertices_inside(m, {"clamp", GroupRegion{"fixed"}})), 3);
    try {
        vertices_inside(m, {"clamp", GroupRegion{"handle"}});
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("region 'clamp': the mesh has no group 'handle' "
                                                   "(groups: fixed)"));
    }
}
