#include "planner/mesh/boundary.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace fibrecell::planner;

namespace {

// A unit cube split into 6 positively oriented tets around the main diagonal 0-6.
TetMesh unit_cube() {
    TetMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back((i & 1) ? 1.0 : 0.0, (i & 2) ? 1.0 : 0.0, (i & 4) ? 1.0 : 0.0);
    // vertex index = x + 2y + 4z; Kuhn triangulation along 0 -> 7.
    const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
    for (auto [a, b] : paths) {
        Tet t = {0, a, b, 7};
        if (signed_volume(m, t) < 0) std::swap(t[1], t[2]);
        m.tets.push_back(t);
    }
    return m;
}

}  // namespace

TEST(Boundary, CubeHasTwelveOutwardTrianglesOfTotalAreaSix) {
    const TetMesh m = unit_cube();
    const auto tris = boundary_triangles(m);
    ASSERT_EQ(tris.size(), 12u);
    double area = 0;
    const Eigen::Vector3d centre(0.5, 0.5, 0.5);
    for (const auto& t : tris) {
        area += triangle_area(m, t);
        const Eigen::Vector3d& a = m.vertices[t.v[0]];
        const Eigen::Vector3d n = (m.vertices[t.v[1]] - a).cross(m.vertices[t.v[2]] - a);
        EXPECT_GT(n.dot(a - centre), 0.0) << "triangle points inward";
    }
    EXPECT_NEAR(area, 6.0, 1e-12);
}
