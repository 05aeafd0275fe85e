#pragma once
// Stress tensors from the flat component lists of mesh files.
//
// 9 components: row-major xx xy xz  yx yy yz  zx zy zz (VTK TENSORS, Gmsh 9-component views).
// 6 components: xx yy zz xy yz xz, the VTK/ParaView symmetric-tensor order (VTK TENSORS6 and
//               6-component SCALARS/FIELD arrays); Gmsh 6-component views are read the same way.
// The comma-separated stress text format has its own order (see stress_text_reader.hpp).

#include "planner/mesh/tet_mesh.hpp"

namespace fibrecell::planner {

// `count` is 6 or 9; `c` points at that many values [MPa].
StressTensor stress_from_components(const double* c, int count);

// True for the component counts a stress array may have.
inline bool is_stress_component_count(long long count) {
    return count == 6 || count == 9;
}

}  // namespace fibrecell::planner
