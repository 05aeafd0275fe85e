#pragma once
// The boundary surface of a tet mesh: faces that belong to exactly one tet.

#include "planner/mesh/adjacency.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <array>
#include <vector>

namespace fibrecell::planner {

struct BoundaryTriangle {
    std::array<int, 3> v;  // vertex indices, counter-clockwise seen from outside the part
    int tet;               // the tet this face belongs to
};

// Returns the boundary triangles of `mesh`, outward oriented. O(#T log #T).
std::vector<BoundaryTriangle> boundary_triangles(const TetMesh& mesh);
// The same from face neighbours already computed.
std::vector<BoundaryTriangle> boundary_triangles(const TetMesh& mesh,
                                                 const FaceNeighbours& neighbours);

// Area of a boundary triangle [mm^2].
double triangle_area(const TetMesh& mesh, const BoundaryTriangle& t);

}  // namespace fibrecell::planner
