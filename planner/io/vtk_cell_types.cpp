#include "planner/io/vtk_cell_types.hpp"

#include <array>
#include <string_view>

namespace fibrecell::planner {
namespace {

struct CellTypeName {
    int id;
    std::string_view name;
};

constexpr std::array kCellTypes = {
    CellTypeName{0, "VTK_EMPTY_CELL"},
    CellTypeName{1, "VTK_VERTEX"},
    CellTypeName{2, "VTK_POLY_VERTEX"},
    CellTypeName{3, "VTK_LINE"},
    CellTypeName{4, "VTK_POLY_LINE"},
    CellTypeName{5, "VTK_TRIANGLE"},
    CellTypeName{6, "VTK_TRIANGLE_STRIP"},
    CellTypeName{7, "VTK_POLYGON"},
    CellTypeName{8, "VTK_PIXEL"},
    CellTypeName{9, "VTK_QUAD"},
    CellTypeName{10, "VTK_TETRA"},
    CellTypeName{11, "VTK_VOXEL"},
    CellTypeName{12, "VTK_HEXAHEDRON"},
    CellTypeName{13, "VTK_WEDGE"},
    CellTypeName{14, "VTK_PYRAMID"},
    CellTypeName{15, "VTK_PENTAGONAL_PRISM"},
    CellTypeName{16, "VTK_HEXAGONAL_PRISM"},
    CellTypeName{21, "VTK_QUADRATIC_EDGE"},
    CellTypeName{22, "VTK_QUADRATIC_TRIANGLE"},
    CellTypeName{23, "VTK_QUADRATIC_QUAD"},
    CellTypeName{24, "VTK_QUADRATIC_TETRA"},
    CellTypeName{25, "VTK_QUADRATIC_HEXAHEDRON"},
    CellTypeName{26, "VTK_QUADRATIC_WEDGE"},
    CellTypeName{27, "VTK_QUADRATIC_PYRAMID"},
    CellTypeName{28, "VTK_BIQUADRATIC_QUAD"},
    CellTypeName{29, "VTK_TRIQUADRATIC_HEXAHEDRON"},
    CellTypeName{30, "VTK_QUADRATIC_LINEAR_QUAD"},
    CellTypeName{31, "VTK_QUADRATIC_LINEAR_WEDGE"},
    CellTypeName{32, "VTK_BIQUADRATIC_QUADRATIC_WEDGE"},
    CellTypeName{33, "VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON"},
    CellTypeName{34, "VTK_BIQUADRATIC_TRIANGLE"},
    CellTypeName{35, "VTK_CUBIC_LINE"},
    CellTypeName{36, "VTK_QUADRATIC_POLYGON"},
    CellTypeName{37, "VTK_TRIQUADRATIC_PYRAMID"},
    CellTypeName{41, "VTK_CONVEX_POINT_SET"},
    CellTypeName{42, "VTK_POLYHEDRON"},
    CellTypeName{71, "VTK_LAGRANGE_TETRAHEDRON"},
    CellTypeName{82, "VTK_BEZIER_TETRAHEDRON"},
};

}  // namespace

std::string vtk_cell_type_name(long long type) {
    for (const CellTypeName& c : kCellTypes)
        if (c.id == type) return std::string(c.name);
    return "unknown cell type";
}

}  // namespace fibrecell::planner
