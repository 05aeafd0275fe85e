#include "planner/io/vtk_reader.hpp"

#include "io_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>

using namespace fibrecell::planner;
using io_test::cube_stress;
using io_test::kCubeTets;
using io_test::replaced;

namespace {

std::string cube_text() {
    return io_test::read_text(io_test::data_path("cube.vtk"));
}

// 1-based line of the first occurrence of `needle` in `text`.
std::size_t line_of(const std::string& text, std::string_view needle) {
    const auto at = text.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::string at_line(std::size_t line) {
    return "line " + std::to_string(line) + ":";
}

void expect_vtk_cube(const VolumeModel& m) {
    ASSERT_EQ(m.mesh.vertex_count(), 8u);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(m.mesh.vertices[i], Eigen::Vector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1)) << i;
    EXPECT_EQ(m.mesh.tets, kCubeTets);
    ASSERT_TRUE(m.stress.has_value());
    ASSERT_EQ(m.stress->size(), 6u);
    for (int i = 0; i < 6; ++i) EXPECT_EQ((*m.stress)[i], cube_stress(i)) << "tet " << i;
    EXPECT_TRUE(m.vertex_groups.empty());
}

// Big-endian binary legacy VTK of the same cube, written the way VTK lays it out: header lines,
// each binary block right after its header line and followed by a newline.
enum class StressLayout { tensors_double, field6_float_named_Stress, scalars6_double };

struct BinaryOptions {
    bool double_points = false;
    bool offsets_layout = false;  // VTK 5.1 OFFSETS/CONNECTIVITY
    StressLayout stress = StressLayout::tensors_double;
};

class BigEndianText {
  public:
    void line(std::string_view s) {
        out_ += s;
        out_ += '\n';
    }
    template <class T>
    void put(T value) {
        char b[sizeof(T)];
        std::memcpy(b, &value, sizeof(T));
        std::reverse(b, b + sizeof(T));
        out_.append(b, sizeof(T));
    }
    void end_block() { out_ += '\n'; }
    const std::string& text() const { return out_; }

  private:
    std::string out_;
};

// Cell order as in cube.vtk: tets 0, 1, a triangle, tets 2..5, a triangle.
struct Cell {
    bool tet;
    int index;  // tet number, or triangle number
};
const Cell kCells[8] = {{true, 0}, {true, 1}, {false, 0}, {true, 2},
                        {true, 3}, {true, 4}, {true, 5},  {false, 1}};
const int kTriangles[2][3] = {{0, 1, 3}, {0, 3, 2}};

std::string binary_cube(const BinaryOptions& o) {
    BigEndianText f;
    f.line(o.offsets_layout ? "# vtk DataFile Version 5.1" : "# vtk DataFile Version 3.0");
    f.line("binary cube");
    f.line("BINARY");
    f.line("DATASET UNSTRUCTURED_GRID");
    f.line("FIELD FieldData 1");
    f.line("TIME 1 1 double");
    f.put(0.5);
    f.end_block();
    f.line(o.double_points ? "POINTS 8 double" : "POINTS 8 float");
    for (int i = 0; i < 8; ++i)
        for (const double c : {double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)})
            o.double_points ? f.put(c) : f.put(static_cast<float>(c));
    f.end_block();
    if (o.offsets_layout) {
        f.line("CELLS 9 30");
        f.line("OFFSETS vtktypeint64");
        std::int64_t offset = 0;
        f.put(offset);
        for (const Cell& c : kCells) f.put(offset += c.tet ? 4 : 3);
        f.end_block();
        f.line("CONNECTIVITY vtktypeint64");
        for (const Cell& c : kCells)
            if (c.tet)
                for (int v : kCubeTets[c.index]) f.put(std::int64_t{v});
            else
                for (int v : kTriangles[c.index]) f.put(std::int64_t{v});
        f.end_block();
    } else {
        f.line("CELLS 8 38");
        for (const Cell& c : kCells) {
            f.put(std::int32_t{c.tet ? 4 : 3});
            if (c.tet)
                for (int v : kCubeTets[c.index]) f.put(std::int32_t{v});
            else
                for (int v : kTriangles[c.index]) f.put(std::int32_t{v});
        }
        f.end_block();
    }
    f.line("CELL_TYPES 8");
    for (const Cell& c : kCells) f.put(std::int32_t{c.tet ? 10 : 5});
    f.end_block();
    f.line("CELL_DATA 8");
    f.line("SCALARS region int 1");
    f.line("LOOKUP_TABLE default");
    for (const Cell& c : kCells) f.put(std::int32_t{c.tet ? 1 : 2});
    f.end_block();
    f.line("COLOR_SCALARS rgb 3");
    for (int i = 0; i < 24; ++i) f.put(static_cast<unsigned char>(i * 10));
    f.end_block();

    auto tensor = [](const Cell& c) {
        return c.tet ? cube_stress(c.index) : StressTensor::Constant(999.0);
    };
    switch (o.stress) {
        case StressLayout::tensors_double:
            f.line("TENSORS stress double");
            for (const Cell& c : kCells) {
                const StressTensor s = tensor(c);
                for (int r = 0; r < 3; ++r)
                    for (int k = 0; k < 3; ++k) f.put(s(r, k));
            }
            f.end_block();
            break;
        case StressLayout::field6_float_named_Stress:
            f.line("FIELD FieldData 3");
            f.line("flags 1 8 bit");
            f.put(static_cast<unsigned char>(0xA5));
            f.end_block();
            f.line("Stress 6 8 float");
            for (const Cell& c : kCells) {
                const StressTensor s = tensor(c);
                for (const double v : {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2)})
                    f.put(static_cast<float>(v));
            }
            f.end_block();
            f.line("ids 1 8 vtkIdType");
            for (int i = 0; i < 8; ++i) f.put(std::int32_t{i});
            f.end_block();
            break;
        case StressLayout::scalars6_double:
            f.line("SCALARS sigma double 6");
            f.line("LOOKUP_TABLE default");
            for (const Cell& c : kCells) {
                const StressTensor s = tensor(c);
                for (const double v : {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2)})
                    f.put(v);
            }
            f.end_block();
            break;
    }
    f.line("POINT_DATA 8");
    f.line("VECTORS displacement double");
    for (int i = 0; i < 24; ++i) f.put(0.01 * i);
    f.end_block();
    return f.text();
}

// A one-tet ASCII file whose CELL_DATA section is `cell_data`.
std::string one_tet(const std::string& cell_data) {
    return "# vtk DataFile Version 2.0\none tet\nASCII\nDATASET UNSTRUCTURED_GRID\n"
           "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
           "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nCELL_DATA 1\n" +
           cell_data;
}

class VtkReader : public ::testing::Test {
  protected:
    // Writes `text` as bad.vtk and expects read_vtk to reject it naming the file and `parts`.
    std::string rejects(const std::string& text, std::initializer_list<std::string_view> parts) {
        const std::string path = dir_.write("bad.vtk", text);
        std::string message = io_test::rejection([&] { read_vtk(path); }, parts);
        EXPECT_NE(message.find(path), std::string::npos) << message;
        return message;
    }
    io_test::TempDir dir_;
};

}  // namespace

TEST_F(VtkReader, ReadsAsciiCubeSkippingTrianglesAndOtherArrays) {
    expect_vtk_cube(read_vtk(io_test::data_path("cube.vtk")));
}

TEST_F(VtkReader, BinaryFilesReadLikeTheAsciiFile) {
    const VolumeModel ascii = read_vtk(io_test::data_path("cube.vtk"));
    for (const bool double_points : {false, true})
        for (const bool offsets : {false, true})
            for (const StressLayout layout :
                 {StressLayout::tensors_double, StressLayout::field6_float_named_Stress,
                  StressLayout::scalars6_double}) {
                SCOPED_TRACE(::testing::Message() << "double " << double_points << " offsets "
                                                  << offsets << " layout " << int(layout));
                const std::string path =
                    dir_.write("cube.vtk", binary_cube({double_points, offsets, layout}));
                const VolumeModel binary = read_vtk(path);
                expect_vtk_cube(binary);
                EXPECT_EQ(binary.mesh.vertices, ascii.mesh.vertices);
                EXPECT_EQ(binary.mesh.tets, ascii.mesh.tets);
                EXPECT_EQ(*binary.stress, *ascii.stress);
            }
}

TEST_F(VtkReader, ReadsABinaryFileWrittenByAnotherProgram) {
    expect_vtk_cube(read_vtk(io_test::data_path("cube_binary.vtk")));  // by Python's struct module
}

TEST_F(VtkReader, ReadsVersion51OffsetsLayoutInAscii) {
    std::string text = cube_text();
    const std::size_t begin = text.find("CELLS 8 38");
    const std::size_t end = text.find("CELL_TYPES");
    text.replace(begin, end - begin,
                 "CELLS 9 30\nOFFSETS vtktypeint64\n0 4 8 11 15 19 23 27 30\n"
                 "CONNECTIVITY vtktypeint64\n0 1 3 7 0 5 1 7 0 1 3 0 3 2 7 0 2 6 7 0 4 5 7 "
                 "0 6 4 7 0 3 2\n"
                 "METADATA\nINFORMATION 0\n\n");
    expect_vtk_cube(read_vtk(dir_.write("cube51.vtk", text)));
}

TEST_F(VtkReader, SixComponentOrderIsXxYyZzXyYzXz) {
    StressTensor expected;
    expected << 1, 4, 6, 4, 2, 5, 6, 5, 3;
    for (const std::string block :
         {"SCALARS s double 6\nLOOKUP_TABLE default\n1 2 3 4 5 6\n",
          "TENSORS6 s double\n1 2 3 4 5 6\n", "FIELD FieldData 1\ns 6 1 double\n1 2 3 4 5 6\n"}) {
        const VolumeModel m = read_vtk(dir_.write("one.vtk", one_tet(block)));
        ASSERT_TRUE(m.stress) << block;
        EXPECT_EQ(m.stress->front(), expected) << block;
    }
}

TEST_F(VtkReader, PrefersTheArrayNamedStressAndIgnoresOthers) {
    const std::string arrays =
        "TENSORS strain double\n9 9 9 9 9 9 9 9 9\n"
        "FIELD FieldData 2\nvon_mises 1 1 float\n3\nSTRESS 9 1 double\n1 2 3 2 5 6 3 6 9\n";
    const VolumeModel m = read_vtk(dir_.write("one.vtk", one_tet(arrays)));
    StressTensor expected;
    expected << 1, 2, 3, 2, 5, 6, 3, 6, 9;
    EXPECT_EQ(m.stress->front(), expected);
}

TEST_F(VtkReader, NoSixOrNineComponentArrayMeansNoStress) {
    const VolumeModel m =
        read_vtk(dir_.write("one.vtk", one_tet("SCALARS a float\nLOOKUP_TABLE default\n1\n")));
    EXPECT_FALSE(m.stress.has_value());
}

TEST_F(VtkReader, SmallAsymmetryIsAveragedAway) {
    const VolumeModel m = read_vtk(
        dir_.write("one.vtk", one_tet("TENSORS stress double\n10 2 0 2.00001 10 0 0 0 10\n")));
    EXPECT_DOUBLE_EQ((*m.stress)[0](0, 1), 2.000005);
    EXPECT_DOUBLE_EQ((*m.stress)[0](1, 0), 2.000005);
}

TEST_F(VtkReader, AllInvertedTetsAreFlippedSilently) {
    std::string text = cube_text();
    for (const Tet& t : kCubeTets) {
        auto s = [](const Tet& x) {
            return "4 " + std::to_string(x[0]) + " " + std::to_string(x[1]) + " " +
                   std::to_string(x[2]) + " " + std::to_string(x[3]) + "\n";
        };
        text = replaced(text, s(t), s({t[0], t[2], t[1], t[3]}));
    }
    const VolumeModel m = read_vtk(dir_.write("inverted.vtk", text));
    EXPECT_TRUE(io_test::all_positive(m.mesh));
    for (int i = 0; i < 6; ++i) EXPECT_EQ((*m.stress)[i], cube_stress(i));
}

// --- rejections: each names the file, the line or the cell, and the problem ---

TEST_F(VtkReader, RejectsMissingFile) {
    EXPECT_REJECTED(read_vtk(dir_.path("nope.vtk")), "nope.vtk", "cannot open");
}

TEST_F(VtkReader, RejectsFilesThatAreNotLegacyVtk) {
    rejects("hello\n", {"line 1:", "not a legacy VTK file"});
    rejects(replaced(cube_text(), "DATASET UNSTRUCTURED_GRID", "DATASET POLYDATA"),
            {"line 4:", "POLYDATA", "UNSTRUCTURED_GRID"});
    rejects(replaced(cube_text(), "ASCII", "TEXT"), {"line 3:", "ASCII or BINARY"});
    rejects(replaced(cube_text(), "CELL_DATA 8", "BOGUS 8"), {"unexpected keyword 'BOGUS'"});
    rejects("", {"not a legacy VTK file"});
}

TEST_F(VtkReader, RejectsNonTetCellsByName) {
    const std::string text = cube_text();
    rejects(replaced(text, "CELL_TYPES 8\n10\n10\n5\n", "CELL_TYPES 8\n10\n10\n12\n"),
            {at_line(29), "cell id 2", "VTK_HEXAHEDRON", "only tetrahedra"});
    rejects(replaced(replaced(text, "CELLS 8 38", "CELLS 8 39"), "4 0 5 1 7", "5 0 5 1 7 2"),
            {at_line(28), "cell id 1", "VTK_TETRA with 5 points"});
}

TEST_F(VtkReader, RejectsBadPointIdsAndRepeatedCorners) {
    const std::string text = cube_text();
    rejects(replaced(text, "4 0 5 1 7", "4 0 5 1 99"),
            {at_line(19), "cell id 1", "point id 99", "8 points"});
    rejects(replaced(text, "4 0 5 1 7", "4 0 5 1 -1"), {at_line(19), "point id -1"});
    rejects(replaced(text, "4 0 5 1 7", "4 0 5 5 7"), {"cell id 1:", "appears twice"});
}

TEST_F(VtkReader, RejectsNonFiniteAndGarbageNumbers) {
    const std::string text = cube_text();
    rejects(replaced(text, "\n1 1 0\n", "\n1 nan 0\n"),
            {at_line(12), "point id 3", "not a finite number"});
    rejects(replaced(text, "\n1 1 0\n", "\n1 inf 0\n"), {at_line(12), "not a finite number"});
    rejects(replaced(text, "\n1 0 0\n", "\n1 x0 0\n"), {at_line(10), "'x0'", "a number"});
    rejects(replaced(text, "4 0 5 1 7", "4 0 5 1 7.5"), {at_line(19), "'7.5'", "integer"});
    const std::string nan_stress = replaced(text, "13 2.5 2.75", "13 nan 2.75");
    rejects(nan_stress,
            {at_line(line_of(text, "13 2.5 2.75")), "stress", "cell id 4", "not a finite number"});
}

TEST_F(VtkReader, RejectsWrongCounts) {
    const std::string text = cube_text();
    rejects(replaced(text, "CELLS 8 38", "CELLS 8 39"), {"CELLS size is 39"});
    rejects(replaced(text, "CELLS 8 38", "CELLS 9 38"), {at_line(26), "'CELL_TYPES'"});
    rejects(replaced(text, "CELL_TYPES 8", "CELL_TYPES 7"),
            {at_line(26), "CELL_TYPES has 7 entries but CELLS has 8 cells"});
    rejects(replaced(text, "CELL_DATA 8", "CELL_DATA 6"),
            {at_line(35), "CELL_DATA 6 does not match the 8 cells"});
    rejects(replaced(text, "POINT_DATA 8", "POINT_DATA 9"), {"POINT_DATA 9"});
    rejects(replaced(text, "velocity 3 8 float", "velocity 3 7 float"), {"has 7 tuples"});
    rejects(replaced(text, "POINTS 8 float", "POINTS -8 float"), {at_line(8), "outside 0.."});
    rejects(replaced(text, "POINTS 8 float", "POINTS 2000000000 float"),
            {at_line(8), "more than the rest of the file can hold"});
    rejects(replaced(text, "CELLS 8 38", "CELLS 8 900000000000"),
            {at_line(17), "more than the rest of the file can hold"});
    rejects(replaced(text, "POINTS 8 float", "POINTS 8 quad"), {"unknown VTK data type 'quad'"});
    rejects(replaced(text, "note 1 8 int", "note 1 8 string"), {"string arrays"});
}

TEST_F(VtkReader, RejectsTruncatedFiles) {
    const std::string text = cube_text();
    rejects(text.substr(0, text.find("1 1 1\n")),
            {at_line(8), "POINTS count 24 is more than the rest of the file can hold"});
    rejects(text.substr(0, text.find("15 3.5 3.25")),
            {"unexpected end of file: expected array 'stress'"});
    rejects(text.substr(0, text.find("CELL_TYPES")), {"no CELL_TYPES section"});
    rejects(text.substr(0, text.find("CELLS")), {"no CELLS section"});
    const std::string binary = binary_cube({});
    rejects(binary.substr(0, binary.find("CELLS 8 38") + 40),
            {at_line(10), "CELLS count 38 is more than the rest of the file can hold"});
}

TEST_F(VtkReader, RejectsBadBinaryContent) {
    std::string binary = binary_cube({});
    // Point 2's y coordinate (float 1.0 = 3F 80 00 00) becomes a NaN.
    const std::size_t points = binary.find("POINTS 8 float\n") + 15;
    std::memcpy(binary.data() + points + 2 * 12 + 4, "\x7f\xc0\x00\x00", 4);
    rejects(binary, {"point id 2", "not a finite number", at_line(8)});
}

TEST_F(VtkReader, RejectsBadGeometry) {
    const std::string text = cube_text();
    rejects(replaced(text, "4 0 5 1 7", "4 5 0 1 7"), {"cell id 1:", "inverted", "1 of 6 tets"});
    rejects(replaced(text, "4 0 1 3 7", "4 0 1 3 2"), {"cell id 0:", "degenerate"});
    rejects(
        "# vtk DataFile Version 2.0\nempty\nASCII\nDATASET UNSTRUCTURED_GRID\n"
        "POINTS 0 float\nCELLS 0 0\nCELL_TYPES 0\n",
        {"empty mesh"});
}

TEST_F(VtkReader, RejectsAmbiguousOrBadStress) {
    rejects(one_tet("TENSORS stress double\n1 2 3 2 5 6 3 6 9\n"
                    "FIELD FieldData 1\nStress 6 1 double\n1 2 3 4 5 6\n"),
            {at_line(18), "second cell array named 'stress'"});
    rejects(one_tet("TENSORS sigma double\n1 2 3 2 5 6 3 6 9\n"
                    "FIELD FieldData 1\neps 6 1 double\n1 2 3 4 5 6\n"),
            {"several 6/9-component cell arrays", "'sigma'", "'eps'"});
    rejects(one_tet("TENSORS stress double\n10 5 0 0 10 0 0 0 10\n"),
            {"cell id 0:", "not symmetric"});
}
