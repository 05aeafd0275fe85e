#include "planner/io/msh_reader.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;
using io_test::cube_stress;
using io_test::kCubeTets;
using io_test::replaced;

namespace {

std::string msh22() {
    return io_test::read_text(io_test::data_path("cube22.msh"));
}
std::string msh41() {
    return io_test::read_text(io_test::data_path("cube41.msh"));
}

// The test files hold the unit cube with scrambled Gmsh node and element tags, an extra node used
// only by a triangle, physical groups "fixed" (bottom triangles) and 7 (all tets, unnamed), and
// views "strain" (6 components) and "stress" (9 components, entries in shuffled order).
void expect_msh_cube(const VolumeModel& m) {
    ASSERT_EQ(m.mesh.vertex_count(), 8u) << "the node used only by a triangle is dropped";
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(m.mesh.vertices[i], Eigen::Vector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1)) << i;
    EXPECT_EQ(m.mesh.tets, kCubeTets);
    ASSERT_TRUE(m.stress.has_value());
    for (int i = 0; i < 6; ++i) EXPECT_EQ((*m.stress)[i], cube_stress(i)) << "tet " << i;
    const std::map<std::string, std::vector<int>> groups = {
        {"fixed", {0, 1, 2, 3}}, {"physical_7", {0, 1, 2, 3, 4, 5, 6, 7}}};
    EXPECT_EQ(m.vertex_groups, groups);
}

class MshReader : public ::testing::Test {
  protected:
    std::string rejects(const std::string& text, std::initializer_list<std::string_view> parts) {
        const std::string path = dir_.write("bad.msh", text);
        std::string message = io_test::rejection([&] { read_msh(path); }, parts);
        EXPECT_NE(message.find(path), std::string::npos) << message;
        return message;
    }
    io_test::TempDir dir_;
};

}  // namespace

TEST_F(MshReader, ReadsMsh22WithGroupsTagRemappingAndStress) {
    expect_msh_cube(read_msh(io_test::data_path("cube22.msh")));
}

TEST_F(MshReader, ReadsMsh41WithEntitiesGroupsAndStress) {
    expect_msh_cube(read_msh(io_test::data_path("cube41.msh")));
}

TEST_F(MshReader, SixComponentViewIsUsedWhenItIsTheOnlyOne) {
    std::string text = msh22();
    text = text.substr(0, text.rfind("$ElementData"));  // drop the "stress" view
    expect_msh_cube(read_msh(dir_.write("strain.msh", text)));
}

TEST_F(MshReader, NonFiniteValuesInAnIgnoredViewDoNoHarm) {
    expect_msh_cube(read_msh(
        dir_.write("ok.msh", replaced(msh22(), "40 10 20 30 1 3 2", "40 nan 20 30 1 3 2"))));
}

TEST_F(MshReader, MeshWithoutElementDataHasNoStress) {
    std::string text = msh41();
    text = text.substr(0, text.find("$ElementData"));
    EXPECT_FALSE(read_msh(dir_.write("plain.msh", text)).stress.has_value());
}

// --- rejections ---

TEST_F(MshReader, RejectsUnsupportedFormats) {
    const std::string text = msh22();
    rejects(replaced(text, "2.2 0 8", "2.2 1 8"),
            {"line 2:", "binary MSH files are not supported"});
    rejects(replaced(text, "2.2 0 8", "4 0 8"), {"line 2:", "MSH 4.0 is not supported"});
    rejects(replaced(text, "2.2 0 8", "3.0 0 8"), {"line 2:", "version '3.0'"});
    rejects("$Nodes\n", {"line 1:", "expected '$MeshFormat'"});
    rejects("", {"unexpected end of file"});
}

TEST_F(MshReader, RejectsSecondOrderAndOtherVolumeElements) {
    const std::string text = msh22();
    rejects(replaced(text, "38 4 2 7 1 31 44 5 61", "38 11 2 7 1 31 44 5 61 7 12 1000 90 5 61"),
            {"line 35:", "second-order tetrahedra (Gmsh type 11)"});
    rejects(replaced(text, "40 4 2 7 1 31 7 12 61", "40 5 2 7 1 31 7 12 61 44 5 90 1000"),
            {"line 31:", "8-node hexahedron elements (Gmsh type 5)"});
    rejects(replaced(text, "40 4 2 7 1", "40 77 2 7 1"),
            {"line 31:", "unknown Gmsh element type 77"});
    rejects(replaced(msh41(), "3 2 4 6", "3 2 11 6"), {"second-order tetrahedra"});
}

TEST_F(MshReader, RejectsBadNodeReferencesAndTags) {
    const std::string text = msh22();
    rejects(replaced(text, "40 4 2 7 1 31 7 12 61", "40 4 2 7 1 31 7 12 62"),
            {"line 31:", "element tag 40", "node tag 62", "not in $Nodes"});
    rejects(replaced(text, "44 0 0 1", "31 0 0 1"), {"line 19:", "node tag 31 appears twice"});
    rejects(replaced(text, "39 4 2 7 1", "38 4 2 7 1"),
            {"line 36:", "element tag 38 appears twice"});
    rejects(replaced(text, "35 4 2 7 1 31 5 7 61", "35 4 2 7 1 31 5 5 61"),
            {"element tag 35:", "appears twice in one tet"});
}

TEST_F(MshReader, RejectsWrongCountsAndTruncation) {
    const std::string text = msh22();
    rejects(replaced(text, "$Nodes\n9\n", "$Nodes\n8\n"),
            {"line 22:", "expected $EndNodes, found '61'", "wrong node count"});
    rejects(replaced(text, "$Nodes\n9\n", "$Nodes\n10\n"), {"line 23:", "'$EndNodes'"});
    rejects(replaced(text, "$Nodes\n9\n", "$Nodes\n-1\n"), {"line 13:", "outside 0.."});
    rejects(replaced(text, "$Nodes\n9\n", "$Nodes\n999999999\n"),
            {"line 13:", "more than the rest of the file can hold"});
    rejects(replaced(text, "$Elements\n11\n", "$Elements\n12\n"), {"line 37:", "'$EndElements'"});
    rejects(text.substr(0, text.find("$EndElements")), {"unexpected end of file"});
    rejects(text.substr(0, text.find("$Elements")), {"no $Elements section"});
    rejects(replaced(text, "7 1 0 0", "7 1 O 0"), {"line 15:", "'O'"});
    rejects(text + "$Foo\n1 2 3\n", {"section $Foo is not closed by $EndFoo"});
    rejects(replaced(text, "$EndComments", "$EndComment"), {"not closed by $EndComments"});
    const std::string v4 = msh41();
    rejects(replaced(v4, "2 9 5 1000", "2 8 5 1000"), {"number of nodes in the block", "outside"});
    rejects(replaced(v4, "3 10 12 40", "3 11 12 40"),
            {"$Elements announces 11 elements but its blocks hold 10"});
}

TEST_F(MshReader, RejectsIncompleteOrAmbiguousStress) {
    const std::string text = msh22();
    // The stress view without element 38.
    std::string missing = replaced(text, "38 14 3 3 3 24 3.5 3 3.5 34\n", "");
    missing = replaced(missing, "0\n9\n6\n", "0\n9\n5\n");
    rejects(missing, {"element tag 38:", "no value in $ElementData view 'stress'"});
    rejects(replaced(text, "39 15 3.5 3.25", "99 15 3.5 3.25"),
            {"element tag 99", "not in $Elements"});
    rejects(replaced(text, "37 13 2.5 2.75", "39 13 2.5 2.75"),
            {"element tag 39 appears twice in this view"});
    rejects(replaced(text, "40 10 1 2 1 20", "40 nan 1 2 1 20"), {"line ", "not a finite number"});
    rejects(replaced(text, "\"stress\"", "\"sigma\""),
            {"several 6/9-component $ElementData views", "'strain'", "'sigma'"});
    rejects(replaced(text, "\"strain\"", "\"STRESS\""),
            {"second $ElementData view named 'stress'", "keep one time step"});
    rejects(replaced(text, "39 15 3.5 3.25 3.5 25", "39 15 9.5 3.25 3.5 25"),
            {"element tag 39:", "not symmetric"});
}

TEST_F(MshReader, RejectsBadGeometry) {
    const std::string text = msh22();
    rejects(replaced(text, "35 4 2 7 1 31 5 7 61", "35 4 2 7 1 5 31 7 61"),
            {"element tag 35:", "inverted", "1 of 6"});
    rejects(replaced(text, "12 1 1 0", "12 0.5 0.5 0.5"), {"element tag 40:", "degenerate"});
}
