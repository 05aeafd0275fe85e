#include "planner/field/mst_reorientation.hpp"

#include "planner/mesh/adjacency.hpp"
#include "planner/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace fibrecell::planner;

namespace {

Eigen::Vector3d centroid(const TetMesh& m, const Tet& t) {
    return (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]] + m.vertices[t[3]]) / 4.0;
}

// Smallest dot product between face neighbours.
double min_neighbour_dot(const std::vector<Eigen::Vector3d>& v, const FaceNeighbours& nb) {
    double worst = 1.0;
    for (std::size_t e = 0; e < v.size(); ++e)
        for (int f : nb[e])
            if (f >= 0) worst = std::min(worst, v[e].dot(v[f]));
    return worst;
}

// Assigns each vector a random sign, as an eigen-solver would.
void scramble_signs(std::vector<Eigen::Vector3d>& v, unsigned seed) {
    std::mt19937 rng(seed);
    for (auto& x : v)
        if (rng() & 1) x = -x;
}

}  // namespace

TEST(MstReorientation, FixesASingleKnownFlip) {
    const TetMesh mesh = structured_tet_mesh({.size = {4, 2, 1}, .cells = {4, 2, 1}});
    std::vector<Eigen::Vector3d> v(mesh.tet_count(), Eigen::Vector3d::UnitX());
    std::vector<double> sigma(mesh.tet_count(), 1.0);
    sigma[0] = 2.0;  // the seed: its orientation is kept
    v[17] = -v[17];
    const auto result = mst_reorient(v, sigma, face_neighbours(mesh));
    EXPECT_EQ(result.flipped, 1);
    EXPECT_EQ(result.components, 1);
    for (const auto& x : v) EXPECT_EQ(x, Eigen::Vector3d::UnitX());
}

TEST(MstReorientation, CircularFieldBecomesConsistentEverywhere) {
    // v = tangential direction around the z axis in a square ring: globally orientable but
    // turning through 360 degrees, with random signs as from an eigen-solver.
    const TetMesh mesh = structured_tet_mesh(
        {.origin = {-10, -10, 0},
         .size = {20, 20, 2},
         .cells = {20, 20, 2},
         .keep_cell = [](const Eigen::Vector3d& c) { return c.head<2>().norm() > 4.0; }});
    std::vector<Eigen::Vector3d> v;
    for (const Tet& t : mesh.tets) {
        const Eigen::Vector3d c = centroid(mesh, t);
        v.push_back(Eigen::Vector3d(-c.y(), c.x(), 0).normalized());
    }
    scramble_signs(v, 3);
    const FaceNeighbours nb = face_neighbours(mesh);
    ASSERT_LT(min_neighbour_dot(v, nb), -0.5);
    const std::vector<double> sigma(v.size(), 1.0);
    mst_reorient(v, sigma, nb);
    EXPECT_GT(min_neighbour_dot(v, nb), 0.0);
}

TEST(MstReorientation, OnlyTheTurbulentRegionStaysInconsistent) {
    // Uniform field with a block of random directions: after re-orientation, negative
    // neighbour products may only touch the block.
    const TetMesh mesh = structured_tet_mesh({.size = {12, 6, 2}, .cells = {12, 6, 2}});
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    std::vector<Eigen::Vector3d> v;
    std::vector<char> turbulent;
    for (const Tet& t : mesh.tets) {
        const Eigen::Vector3d c = centroid(mesh, t);
        const bool in_block = c.x() > 5 && c.x() < 7 && c.y() > 2 && c.y() < 4;
        turbulent.push_back(in_block);
        v.push_back(in_block ? Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized()
                             : Eigen::Vector3d(1, 0.2, 0).normalized());
    }
    scramble_signs(v, 5);
    const FaceNeighbours nb = face_neighbours(mesh);
    const std::vector<double> sigma(v.size(), 1.0);
    const auto result = mst_reorient(v, sigma, nb);
    for (std::size_t e = 0; e < v.size(); ++e)
        for (int f : nb[e])
            if (f >= 0 && v[e].dot(v[f]) < 0) {
                EXPECT_TRUE(turbulent[e] || turbulent[f]) << "elements " << e << " and " << f;
            }
    // Every tree edge agrees by construction.
    for (std::size_t e = 0; e < v.size(); ++e)
        if (result.parent[e] >= 0) {
            EXPECT_GE(v[e].dot(v[result.parent[e]]), 0.0);
        }
}

TEST(MstReorientation, SeedsEveryComponentAtItsLargestStress) {
    // Two separate blocks: two components, each keeps the sign of its strongest element.
    const TetMesh mesh = structured_tet_mesh(
        {.size = {5, 1, 1}, .cells = {5, 1, 1}, .keep_cell = [](const Eigen::Vector3d& c) {
             return c.x() < 2 || c.x() > 3;
         }});
    std::vector<Eigen::Vector3d> v(mesh.tet_count(), Eigen::Vector3d::UnitY());
    std::vector<double> sigma(mesh.tet_count(), 1.0);
    const int last = static_cast<int>(mesh.tet_count()) - 1;
    v[last] = -v[last];
    sigma[last] = 5.0;  // the second block's seed points along -y
    const auto result = mst_reorient(v, sigma, face_neighbours(mesh));
    EXPECT_EQ(result.components, 2);
    for (std::size_t e = 0; e < v.size(); ++e) {
        const bool second_block = centroid(mesh, mesh.tets[e]).x() > 3;
        EXPECT_EQ(v[e], second_block ? Eigen::Vector3d(-Eigen::Vector3d::UnitY())
                                     : Eigen::Vector3d::UnitY());
    }
}
