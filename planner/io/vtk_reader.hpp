#pragma once
// Reader for legacy VTK unstructured grids of tetrahedra, with optional per-cell stress.

#include "planner/mesh/tet_mesh.hpp"

#include <string>
#include <string_view>

namespace fibrecell::planner {

// Reads a legacy VTK DATASET UNSTRUCTURED_GRID, ASCII or BINARY (big-endian, any numeric point
// type; classic CELLS lists or the OFFSETS/CONNECTIVITY layout of file version 5.1).
//
// Cells: VTK_TETRA (10) become the mesh; VTK_TRIANGLE (5) cells are skipped (some exporters add
// the surface); any other cell type is rejected by name.
// Stress: a CELL_DATA array with 6 or 9 components (TENSORS, TENSORS6, SCALARS with 6/9
// components, or a FIELD array); the one named "stress" (any case) when there is one, else the
// only such array. Component orders: see stress_components.hpp. Other arrays are skipped.
//
// Throws InputError naming the file and the line, or the cell/point by its 0-based VTK id
// ("cell id 4"), for anything malformed; the result has passed validate_model.
VolumeModel read_vtk(const std::string& path);

// The same for a file already in memory; `file` names it in messages.
VolumeModel parse_vtk(std::string_view text, const std::string& file);

}  // namespace fibrecell::planner
