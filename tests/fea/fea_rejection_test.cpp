// Load cases without a unique solution are refused with a message that says what to fix.

#include "planner/fea/fea_error.hpp"
#include "planner/fea/linear_elastic.hpp"

#include "fea_test_meshes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

using namespace fibrecell::planner;
using namespace fibrecell::planner::fea_test;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

// A 20 x 10 x 10 block held at x = 0 and pushed sideways at x = 20.
struct Block {
    TetMesh mesh = box_mesh({20, 10, 10}, 4, 2, 2);
    LoadCase load_case;
    Block() {
        load_case.supports.push_back(
            {"clamp", vertices_where(mesh, [](const Eigen::Vector3d& p) { return p.x() < kTol; })});
        load_case.loads.push_back(
            {"push",
             boundary_where(mesh, [](const Eigen::Vector3d& p) { return p.x() > 20 - kTol; }),
             {0, 100, 0}});
    }
};

// Message of the FeaError the solve throws, or "" when it throws none.
std::string rejection(const TetMesh& mesh, const LoadCase& load_case,
                      const FeaOptions& options = {}) {
    try {
        solve_linear_elastic(mesh, load_case, options);
    } catch (const FeaError& e) {
        return e.what();
    }
    return "";
}

// Two meshes side by side in one TetMesh, not sharing any vertex.
TetMesh two_blocks(const TetMesh& a, TetMesh b, const Eigen::Vector3d& offset) {
    for (Eigen::Vector3d& p : b.vertices) p += offset;
    return merge_meshes({a, b});
}

}  // namespace

TEST(FeaRejection, TheBlockItselfSolves) {
    const Block b;
    EXPECT_EQ(rejection(b.mesh, b.load_case), "");
}

TEST(FeaRejection, NoSupports) {
    Block b;
    b.load_case.supports.clear();
    EXPECT_THAT(rejection(b.mesh, b.load_case), HasSubstr("no supports"));
}

TEST(FeaRejection, SupportRegionWithoutVertices) {
    Block b;
    b.load_case.supports.push_back({"pin_left", {}});
    EXPECT_THAT(rejection(b.mesh, b.load_case),
                AllOf(HasSubstr("support region 'pin_left'"), HasSubstr("no vertices")));
}

TEST(FeaRejection, LoadRegionWithoutTriangles) {
    Block b;
    b.load_case.loads.push_back({"pin_right", {}, {1, 0, 0}});
    EXPECT_THAT(rejection(b.mesh, b.load_case),
                AllOf(HasSubstr("load region 'pin_right'"), HasSubstr("no triangles")));
}

TEST(FeaRejection, RegionWithVertexOutsideTheMesh) {
    Block b;
    b.load_case.supports[0].vertices.push_back(100000);
    EXPECT_THAT(rejection(b.mesh, b.load_case),
                AllOf(HasSubstr("support region 'clamp'"), HasSubstr("vertex 100000")));
}

TEST(FeaRejection, YoungsModulusMustBePositive) {
    Block b;
    for (double e : {0.0, -3500.0}) {
        b.load_case.material.youngs_modulus_mpa = e;
        EXPECT_THAT(rejection(b.mesh, b.load_case), HasSubstr("Young's modulus must be positive"));
    }
}

TEST(FeaRejection, PoissonRatioMustLieBetweenMinusOneAndHalf) {
    Block b;
    for (double nu : {0.5, 0.6, -1.0}) {
        b.load_case.material.poisson_ratio = nu;
        EXPECT_THAT(rejection(b.mesh, b.load_case),
                    HasSubstr("Poisson's ratio must lie in (-1, 0.5)"));
    }
    b.load_case.material.poisson_ratio = 0.49;  // nearly incompressible is still fine
    EXPECT_EQ(rejection(b.mesh, b.load_case), "");
}

TEST(FeaRejection, InvertedTet) {
    Block b;
    std::swap(b.mesh.tets[7][1], b.mesh.tets[7][2]);
    EXPECT_THAT(rejection(b.mesh, b.load_case), HasSubstr("tet 7 is inverted or flat"));
}

// A second block 50 mm along x, loaded but held nowhere: the message counts the parts and
// describes the floating one by size and place.
TEST(FeaRejection, PartWithoutSupport) {
    const Block b;
    const TetMesh mesh = two_blocks(b.mesh, b.mesh, {50, 0, 0});
    EXPECT_THAT(rejection(mesh, b.load_case),
                AllOf(HasSubstr("2 connected parts"), HasSubstr("1 of them has no fixed vertex"),
                      HasSubstr("part 2 (45 vertices, box [50, 0, 0]-[70, 10, 10] mm)")));
}

TEST(FeaRejection, SupportsOnOneLine) {
    Block b;
    b.load_case.supports[0].vertices = vertices_where(
        b.mesh, [](const Eigen::Vector3d& p) { return p.x() < kTol && p.z() < kTol; });
    EXPECT_THAT(
        rejection(b.mesh, b.load_case),
        AllOf(HasSubstr("part 1"),
              HasSubstr("all lie on one line (3 fixed vertices from [0, 0, 0] to [0, 10, 0])"),
              HasSubstr("rotate")));
}

TEST(FeaRejection, SupportAtOnePoint) {
    Block b;
    b.load_case.supports[0].vertices = {0, 0};
    EXPECT_THAT(rejection(b.mesh, b.load_case),
                HasSubstr("part 1 (45 vertices, box [0, 0, 0]-[20, 10, 10] mm) is held at one "
                          "point only, [0, 0, 0] (1 fixed vertex)"));
}

// Two cubes sharing only an edge are one part by shared vertices, and the supports of the first
// are fine, yet the second can turn about the shared edge: only the factorisation can tell.
TEST(FeaRejection, HingedPartsMakeTheStiffnessSingular) {
    const TetMesh cube = box_mesh({10, 10, 10}, 2, 2, 2);
    TetMesh mesh = cube;
    TetMesh second = cube;
    for (Eigen::Vector3d& p : second.vertices) p += Eigen::Vector3d(10, 10, 0);
    mesh = merge_meshes({cube, second});  // share the edge x = y = 10
    LoadCase lc;
    lc.supports.push_back(
        {"base", vertices_where(mesh, [](const Eigen::Vector3d& p) { return p.x() < kTol; })});
    lc.loads.push_back(
        {"tip",
         boundary_where(mesh, [](const Eigen::Vector3d& p) { return p.x() > 20 - kTol; }),
         {0, 10, 0}});
    for (LinearSolver solver :
         {LinearSolver::cholmod_supernodal, LinearSolver::eigen_simplicial_ldlt}) {
        FeaOptions options;
        options.solver = solver;
        EXPECT_THAT(rejection(mesh, lc, options),
                    AllOf(HasSubstr("stiffness matrix is singular"), HasSubstr("joined only at")))
            << solver_name(solver);
    }
}

// Rounding can leave a mechanism's pivot tiny but positive; the ratio test catches it. Here a
// sound block with an absurd threshold stands in for that case.
TEST(FeaRejection, PivotBelowTheSingularRatio) {
    const Block b;
    FeaOptions options;
    options.singular_pivot_ratio = 0.999;
    EXPECT_THAT(rejection(b.mesh, b.load_case, options),
                AllOf(HasSubstr("stiffness matrix is singular (pivot 0."),
                      HasSubstr("of its diagonal at the")));
}

// Gmsh keeps geometry points that no tet uses; holding only those holds nothing.
TEST(FeaRejection, SupportOnVerticesNoTetUses) {
    Block b;
    b.mesh.vertices.emplace_back(-5, 0, 0);
    b.load_case.supports[0].vertices = {static_cast<int>(b.mesh.vertex_count()) - 1};
    EXPECT_THAT(rejection(b.mesh, b.load_case),
                AllOf(HasSubstr("no support holds a vertex of the mesh"), HasSubstr("part 1")));
}

TEST(FeaRejection, LoadOnVertexNoTetUses) {
    Block b;
    b.mesh.vertices.emplace_back(-5, 0, 0);
    b.load_case.loads[0].triangles[0].v[0] = static_cast<int>(b.mesh.vertex_count()) - 1;
    EXPECT_THAT(rejection(b.mesh, b.load_case),
                AllOf(HasSubstr("load region 'push'"), HasSubstr("belongs to no tet")));
}

TEST(FeaRejection, AnAddedStiffnessMustFitTheMeshAndBeSymmetric) {
    Block b;
    b.load_case.added_stiffness.assign(b.mesh.tet_count() - 1, VoigtStiffness::Zero());
    EXPECT_THAT(rejection(b.mesh, b.load_case), HasSubstr("entries for a mesh of"));
    b.load_case.added_stiffness.assign(b.mesh.tet_count(), VoigtStiffness::Zero());
    EXPECT_EQ(rejection(b.mesh, b.load_case), "");
    b.load_case.added_stiffness[7](0, 1) = 100;  // (1, 0) stays 0
    EXPECT_THAT(rejection(b.mesh, b.load_case), HasSubstr("tet 7 is not symmetric"));
}
