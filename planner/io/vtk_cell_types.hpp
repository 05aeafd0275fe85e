#pragma once
// Names of VTK cell types, so that a rejected cell is named the way VTK documents it.

#include <string>

namespace fibrecell::planner {

constexpr int kVtkTriangle = 5;
constexpr int kVtkTetra = 10;

// "VTK_HEXAHEDRON" for 12, "unknown cell type" for ids VTK does not define.
std::string vtk_cell_type_name(long long type);

}  // namespace fibrecell::planner
