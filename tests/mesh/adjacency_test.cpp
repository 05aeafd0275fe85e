#include "planner/mesh/adjacency.hpp"

#include "planner/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace fibrecell::planner;

namespace {

int shared_vertices(const Tet& a, const Tet& b) {
    int n = 0;
    for (int x : a) n += static_cast<int>(std::count(b.begin(), b.end(), x));
    return n;
}

}  // namespace

TEST(Adjacency, FaceNeighboursShareExactlyThreeVerticesAndAreSymmetric) {
    const TetMesh m = structured_tet_mesh({.size = {3, 2, 2}, .cells = {3, 2, 2}});
    const auto nb = face_neighbours(m);
    int interior_faces = 0;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        for (int f = 0; f < 4; ++f) {
            const int u = nb[t][f];
            if (u < 0) continue;
            ++interior_faces;
            EXPECT_EQ(shared_vertices(m.tets[t], m.tets[u]), 3);
            // The shared face is the one opposite local vertex f.
            EXPECT_EQ(std::count(m.tets[u].begin(), m.tets[u].end(), m.tets[t][f]), 0);
            EXPECT_NE(std::find(nb[u].begin(), nb[u].end(), static_cast<int>(t)), nb[u].end());
        }
    }
    // 12 cells * 6 tets * 4 faces = 288 faces; the box surface has 2*(6+6+4)=32 squares = 64
    // triangles, so 224 face-sides are interior.
    EXPECT_EQ(interior_faces, 288 - 64);
}

TEST(Adjacency, VertexSharingNeighboursMatchBruteForce) {
    const TetMesh m = structured_tet_mesh({.size = {2, 2, 2}, .cells = {2, 2, 2}});
    const CsrGraph g = vertex_sharing_neighbours(m);
    ASSERT_EQ(g.node_count(), m.tets.size());
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        std::vector<int> expected;
        for (std::size_t u = 0; u < m.tets.size(); ++u)
            if (u != t && shared_vertices(m.tets[t], m.tets[u]) > 0)
                expected.push_back(static_cast<int>(u));
        const auto got = g.neighbours(static_cast<int>(t));
        EXPECT_EQ(std::vector<int>(got.begin(), got.end()), expected) << "tet " << t;
    }
}

TEST(StructuredMesh, VolumeAndOrientation) {
    const TetMesh m =
        structured_tet_mesh({.origin = {1, 2, 3}, .size = {3, 2, 1}, .cells = {3, 4, 2}});
    EXPECT_EQ(m.tets.size(), 6u * 24);
    EXPECT_EQ(m.vertices.size(), 4u * 5 * 3);
    double volume = 0;
    for (const Tet& t : m.tets) {
        EXPECT_GT(signed_volume(m, t), 0.0);
        volume += signed_volume(m, t);
    }
    EXPECT_NEAR(volume, 6.0, 1e-12);
}
