#include "planner/io/read_model.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;

namespace {

std::string data(const std::string& name) {
    return io_test::read_text(io_test::data_path(name));
}

}  // namespace

TEST(ReadVolumeModel, DispatchesByExtensionInAnyCase) {
    io_test::TempDir dir;
    EXPECT_EQ(read_volume_model(dir.write("a.VTK", data("cube.vtk"))).mesh.tet_count(), 6u);
    EXPECT_EQ(read_volume_model(dir.write("b.Msh", data("cube41.msh"))).mesh.tet_count(), 6u);
    EXPECT_EQ(read_volume_model(dir.write("c.tet", data("cube.tet"))).mesh.tet_count(), 6u);
}

TEST(ReadVolumeModel, TetFindsItsSelectionFileButNotItsStress) {
    io_test::TempDir dir;
    const std::string tet = dir.write("part.tet", data("cube.tet"));
    dir.write("part_stress.txt", data("cube_stress.txt"));
    VolumeModel m = read_volume_model(tet);
    EXPECT_FALSE(m.stress);
    EXPECT_TRUE(m.vertex_groups.empty());

    dir.write("part_selection.txt", data("cube_selection.txt"));
    m = read_volume_model(tet, dir.path("part_stress.txt"));
    ASSERT_TRUE(m.stress);
    EXPECT_EQ((*m.stress)[5], io_test::cube_stress(5));
    EXPECT_EQ(m.vertex_groups.at("fixed"), (std::vector<int>{0, 1, 2, 3}));
}

TEST(ReadVolumeModel, StressFileReplacesTheMeshFilesStress) {
    io_test::TempDir dir;
    const std::string stress = dir.write("s.txt",
                                         "1,0,1,1,1,0,0,0\n2,0,2,2,2,0,0,0\n3,0,3,3,3,0,0,0\n"
                                         "4,0,4,4,4,0,0,0\n5,0,5,5,5,0,0,0\n6,0,6,6,6,0,0,0\n");
    for (const char* mesh : {"cube.vtk", "cube22.msh"}) {
        const VolumeModel m = read_volume_model(io_test::data_path(mesh), stress);
        ASSERT_TRUE(m.stress);
        for (int i = 0; i < 6; ++i)
            EXPECT_EQ((*m.stress)[i], StressTensor::Identity() * (i + 1)) << mesh;
    }
}

TEST(ReadVolumeModel, RejectsUnknownExtensionsAndBadStressFiles) {
    io_test::TempDir dir;
    EXPECT_REJECTED(read_volume_model(dir.write("m.stl", "solid x\n")), "m.stl",
                    "unknown mesh format '.stl'");
    EXPECT_REJECTED(read_volume_model(dir.write("noext", "")), "noext", "unknown mesh format");
    const std::string bad = dir.write("s.txt", "1,0,1,1,1,0,0,0\n");
    EXPECT_REJECTED(read_volume_model(io_test::data_path("cube.vtk"), bad),
                    bad + ": element 2:", "no stress line");
    EXPECT_REJECTED(read_volume_model(io_test::data_path("cube.vtk"), dir.path("none.txt")),
                    "none.txt", "cannot open");
}
