#include "planner/io/tet_reader.hpp"
#include "planner/io/selection_reader.hpp"
#include "planner/io/stress_text_reader.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

using namespace fibrecell::planner;
using io_test::cube_stress;
using io_test::kCubeTets;
using io_test::replaced;

namespace {

std::string tet_text() {
    return io_test::read_text(io_test::data_path("cube.tet"));
}
std::string stress_text() {
    return io_test::read_text(io_test::data_path("cube_stress.txt"));
}
std::string selection_text() {
    return io_test::read_text(io_test::data_path("cube_selection.txt"));
}

class TetReader : public ::testing::Test {
  protected:
    // Writes the three files (any may be replaced) and reads them with read_tet.
    VolumeModel read(const std::string& tet, const std::string& stress,
                     const std::string& selection) {
        return read_tet(dir_.write("m.tet", tet), dir_.write("m_stress.txt", stress),
                        dir_.write("m_selection.txt", selection));
    }
    void rejects(const std::string& tet, const std::string& stress, const std::string& selection,
                 const std::string& bad_file, std::initializer_list<std::string_view> parts) {
        const std::string message =
            io_test::rejection([&] { read(tet, stress, selection); }, parts);
        EXPECT_NE(message.find(dir_.path(bad_file).string() + ":"), std::string::npos) << message;
    }
    io_test::TempDir dir_;
};

}  // namespace

TEST_F(TetReader, ReadsMeshStressAndSelection) {
    const VolumeModel m =
        read_tet(io_test::data_path("cube.tet"), io_test::data_path("cube_stress.txt"),
                 io_test::data_path("cube_selection.txt"));
    ASSERT_EQ(m.mesh.vertex_count(), 8u);
    EXPECT_EQ(m.mesh.vertices[6], Eigen::Vector3d(0, 1, 1));
    EXPECT_EQ(m.mesh.tets, kCubeTets);
    ASSERT_TRUE(m.stress);
    for (int i = 0; i < 6; ++i) EXPECT_EQ((*m.stress)[i], cube_stress(i)) << i;
    const std::map<std::string, std::vector<int>> groups = {{"fixed", {0, 1, 2, 3}},
                                                            {"handle", {5, 7}}};
    EXPECT_EQ(m.vertex_groups, groups);
}

TEST_F(TetReader, StressAndSelectionAreOptional) {
    const VolumeModel m = read_tet(io_test::data_path("cube.tet"), "", "");
    EXPECT_EQ(m.mesh.tet_count(), 6u);
    EXPECT_FALSE(m.stress);
    EXPECT_TRUE(m.vertex_groups.empty());
}

TEST_F(TetReader, StressAndSelectionLinesMayComeInAnyOrder) {
    const std::string stress = stress_text();
    const std::size_t third = stress.find("\n3,") + 1;
    const std::string reordered = stress.substr(third) + "\n\n" + stress.substr(0, third);
    const std::string selection = "8:0:1\n" + replaced(selection_text(), "8:0:1:\n", "");
    const VolumeModel m = read(tet_text(), reordered, selection);
    for (int i = 0; i < 6; ++i) EXPECT_EQ((*m.stress)[i], cube_stress(i)) << i;
    EXPECT_EQ(m.vertex_groups.at("handle"), (std::vector<int>{5, 7}));
}

TEST_F(TetReader, RejectsBadTetFiles) {
    const std::string s = stress_text(), sel = selection_text();
    const std::string t = tet_text();
    rejects(replaced(t, "8 vertices", "8 points"), s, sel, "m.tet",
            {"line 1:", "expected 'vertices'"});
    rejects(replaced(t, "6 tets", "-6 tets"), s, sel, "m.tet", {"line 2:", "outside 0.."});
    rejects(replaced(t, "8 vertices", "900000000 vertices"), s, sel, "m.tet",
            {"line 1:", "more than the rest of the file can hold"});
    rejects(replaced(t, "\n1 1 0\n", "\n1 nan 0\n"), s, sel, "m.tet",
            {"line 6:", "not a finite number"});
    rejects(replaced(t, "\n1 1 0\n", "\n1 1,0 0\n"), s, sel, "m.tet", {"line 6:", "'1,0'"});
    rejects(replaced(t, "4 0 5 1 7", "3 0 5 1"), s, sel, "m.tet",
            {"line 12:", "must start with 4"});
    rejects(replaced(t, "4 0 5 1 7", "4 0 5 1 8"), s, sel, "m.tet",
            {"line 12:", "vertex index 8 is out of range"});
    rejects(replaced(t, "4 0 5 1 7", "4 0 5 0 7"), s, sel, "m.tet", {"line 12:", "appears twice"});
    rejects(replaced(t, "6 tets", "7 tets"), s, sel, "m.tet", {"unexpected end of file"});
    rejects(replaced(t, "6 tets", "5 tets"), s, sel, "m.tet",
            {"line 16:", "after the last of 5 tets"});
    rejects(t.substr(0, t.find("1 1 1")), s, sel, "m.tet",
            {"line 2:", "tet count 6 is more than the rest of the file can hold"});
    rejects(t.substr(0, t.find("4 0 6 4 7")), s, sel, "m.tet", {"unexpected end of file"});
    rejects(replaced(t, "4 0 5 1 7", "4 5 0 1 7"), s, sel, "m.tet",
            {"element 2:", "inverted", "1 of 6"});
    rejects("0 vertices\n0 tets\n", s, sel, "m.tet", {"empty mesh"});
}

TEST_F(TetReader, RejectsBadStressFiles) {
    const std::string t = tet_text(), sel = selection_text();
    const std::string s = stress_text();
    rejects(t, replaced(s, "2,31,", "2,31,,"), sel, "m_stress.txt",
            {"line 2:", "expected 8 comma-separated fields", "found 9"});
    rejects(t, replaced(s, "3,32,12", "3,32"), sel, "m_stress.txt", {"line 3:", "found 7"});
    rejects(t, replaced(s, "2,31,11", "2,31,1x1"), sel, "m_stress.txt",
            {"line 2:", "expected S11", "'1x1'"});
    rejects(t, replaced(s, "2,31,11", "2,31,nan"), sel, "m_stress.txt",
            {"line 2:", "S11 is not a finite number"});
    rejects(t, replaced(s, "\n4,", "\n2,"), sel, "m_stress.txt",
            {"line 4:", "element id 2 appears twice (first on line 2)"});
    rejects(t, replaced(s, "\n4,", "\n7,"), sel, "m_stress.txt",
            {"line 4:", "element id 7 is outside 1..6"});
    rejects(t, replaced(s, "\n4,", "\nfour,"), sel, "m_stress.txt",
            {"line 4:", "expected an element id"});
    rejects(t, s.substr(0, s.find("\n5,") + 1), sel, "m_stress.txt",
            {"element 5:", "no stress line", "4 of 6"});
}

TEST_F(TetReader, RejectsBadSelectionFiles) {
    const std::string t = tet_text(), s = stress_text();
    const std::string sel = selection_text();
    rejects(t, s, replaced(sel, "6:0:1:", "6:0:2:"), "m_selection.txt",
            {"line 6:", "handle flag must be 0 or 1"});
    rejects(t, s, replaced(sel, "6:0:1:", "6:0"), "m_selection.txt",
            {"line 6:", "expected 'vertexId:fixed:handle:'"});
    rejects(t, s, replaced(sel, "6:0:1:", "5:0:1:"), "m_selection.txt",
            {"line 6:", "vertex id 5 appears twice"});
    rejects(t, s, replaced(sel, "6:0:1:", "9:0:1:"), "m_selection.txt",
            {"line 6:", "vertex id 9 is outside 1..8"});
    rejects(t, s, replaced(sel, "6:0:1:\n", ""), "m_selection.txt",
            {"vertex 6:", "no selection line", "7 of 8"});
}

TEST(StressText, ComponentOrderIsS11S22S33S12S13S23) {
    const auto stress = parse_stress_text("1, 0, 1, 2, 3, 4, 5, 6\n", "s.txt", 1);
    StressTensor expected;
    expected << 1, 4, 5, 4, 2, 6, 5, 6, 3;
    EXPECT_EQ(stress.at(0), expected);
}

TEST(Selection, TrailingColonIsOptional) {
    const auto groups = parse_selection("1:1:0\n2:0:1:\n", "sel.txt", 2);
    EXPECT_EQ(groups.at("fixed"), std::vector<int>{0});
    EXPECT_EQ(groups.at("handle"), std::vector<int>{1});
}
