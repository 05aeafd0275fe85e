#include "planner/io/validate_model.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

#include <limits>

using namespace fibrecell::planner;

namespace {

// The unit cube: vertex i = (i&1, i>>1&1, i>>2&1), six positive tets, stress per tet.
VolumeModel cube() {
    VolumeModel m;
    for (int i = 0; i < 8; ++i) m.mesh.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    m.mesh.tets = {{0, 1, 3, 7}, {0, 5, 1, 7}, {0, 3, 2, 7},
                   {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 6, 4, 7}};
    m.stress.emplace();
    for (int i = 0; i < 6; ++i) m.stress->push_back(io_test::cube_stress(i));
    m.vertex_groups["fixed"] = {3, 1, 0, 2, 1};
    return m;
}

}  // namespace

TEST(ValidateModel, AcceptsAGoodModelAndTidiesGroups) {
    VolumeModel m = cube();
    validate_model(m, "cube.vtk");
    EXPECT_EQ(m.vertex_groups.at("fixed"), (std::vector<int>{0, 1, 2, 3}));
    EXPECT_TRUE(io_test::all_positive(m.mesh));
}

TEST(ValidateModel, FlipsAMeshWhoseTetsAreAllInverted) {
    VolumeModel m = cube();
    for (Tet& t : m.mesh.tets) std::swap(t[0], t[1]);
    validate_model(m, "cube.vtk");
    EXPECT_TRUE(io_test::all_positive(m.mesh));
    for (int i = 0; i < 6; ++i) EXPECT_EQ((*m.stress)[i], io_test::cube_stress(i));
}

TEST(ValidateModel, RejectsMixedOrientationNamingTheFirstInvertedTet) {
    VolumeModel m = cube();
    std::swap(m.mesh.tets[2][0], m.mesh.tets[2][1]);
    std::swap(m.mesh.tets[4][0], m.mesh.tets[4][1]);
    EXPECT_REJECTED(validate_model(m, "cube.vtk"), "cube.vtk: element 3: inverted",
                    "2 of 6 tets are inverted");
}

TEST(ValidateModel, RejectsEmptyMeshes) {
    VolumeModel m;
    EXPECT_REJECTED(validate_model(m, "e.msh"), "e.msh: empty mesh");
    m.mesh.tets.push_back({0, 1, 2, 3});
    EXPECT_REJECTED(validate_model(m, "e.msh"), "e.msh: empty mesh: no vertices");
}

TEST(ValidateModel, RejectsNonFiniteCoordinatesNamingTheVertex) {
    VolumeModel m = cube();
    m.mesh.vertices[4].y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_REJECTED(validate_model(m, "c.vtk"), "c.vtk: vertex 5: coordinate is not a finite");
    m = cube();
    m.mesh.vertices[0].x() = std::numeric_limits<double>::infinity();
    FileNumbering vtk{"cell id", "point id", 0, {}, {}};
    EXPECT_REJECTED(validate_model(m, "c.vtk", vtk), "c.vtk: point id 0: coordinate");
}

TEST(ValidateModel, RejectsBadIndicesNamingTheElement) {
    VolumeModel m = cube();
    m.mesh.tets[1][3] = 8;
    EXPECT_REJECTED(validate_model(m, "c.tet"), "c.tet: element 2: vertex index 8 is out of range");
    m = cube();
    m.mesh.tets[5][0] = -1;
    FileNumbering gmsh{"element tag", "node tag", 1, {10, 11, 12, 13, 14, 99}, {}};
    EXPECT_REJECTED(validate_model(m, "c.msh", gmsh), "c.msh: element tag 99: vertex index -1");
    m = cube();
    m.mesh.tets[0][2] = m.mesh.tets[0][0];
    EXPECT_REJECTED(validate_model(m, "c.tet"), "element 1: vertex index 0 appears twice");
}

TEST(ValidateModel, RejectsDegenerateTets) {
    VolumeModel m = cube();
    m.mesh.vertices.emplace_back(0.5, 0.5, 0.0);  // on the face z = 0 of tet 0
    m.mesh.tets[0] = {0, 1, 3, 8};
    EXPECT_REJECTED(validate_model(m, "c.tet"), "element 1: degenerate tet");
    // A sliver just above the threshold is still a tet.
    m.mesh.vertices[8].z() = 1e-6;
    m.stress.reset();
    validate_mesh(m.mesh, "c.tet");
}

TEST(ValidateModel, RejectsStressProblems) {
    VolumeModel m = cube();
    m.stress->pop_back();
    EXPECT_REJECTED(validate_model(m, "s.txt"), "s.txt: 5 stress tensors for 6 tets");
    m = cube();
    (*m.stress)[3](2, 2) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_REJECTED(validate_model(m, "s.txt"), "s.txt: element 4: stress is not a finite");
    m = cube();
    (*m.stress)[1](0, 2) += 1.0;  // 1 against components of about 31
    EXPECT_REJECTED(validate_model(m, "s.vtk"), "element 2: stress tensor is not symmetric");
}

TEST(ValidateModel, AveragesRoundOffAsymmetry) {
    VolumeModel m = cube();
    (*m.stress)[1](0, 2) += 1e-5;
    validate_model(m, "s.vtk");
    EXPECT_EQ((*m.stress)[1](0, 2), (*m.stress)[1](2, 0));
    EXPECT_NEAR((*m.stress)[1](0, 2), io_test::cube_stress(1)(0, 2) + 0.5e-5, 1e-12);
}

TEST(ValidateModel, RejectsGroupsOutsideTheMesh) {
    VolumeModel m = cube();
    m.vertex_groups["handle"] = {2, 8};
    EXPECT_REJECTED(validate_model(m, "sel.txt"), "sel.txt: vertex group 'handle'",
                    "vertex index 8");
}
