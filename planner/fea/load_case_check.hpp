#pragma once
// Rejects load cases without a unique static solution before any matrix is built, with messages
// that name the region or the mesh part at fault.

#include "planner/fea/linear_elastic.hpp"

#include <cstdint>
#include <vector>

namespace fibrecell::planner {

// Per-vertex flags the assembly needs once the load case is known to be solvable.
struct VertexRoles {
    std::vector<std::uint8_t> used;   // #V, 1 when some tet references the vertex
    std::vector<std::uint8_t> fixed;  // #V, 1 when a support holds it (only used vertices)
};

// Throws FeaError when: the material is out of range; there is no support; a region is empty,
// has out-of-range indices or (for loads) zero area; a tet is inverted or flat; a mesh part has
// no fixed vertex; or the fixed vertices of a part all lie on one line.
VertexRoles check_load_case(const TetMesh& mesh, const LoadCase& load_case);

}  // namespace fibrecell::planner
