#pragma once
// The outline of a layer: the boundary of its triangle mesh T, chained into closed loops.

#include "planner/layers/layer_mesh.hpp"

namespace fibrecell::planner {

// layer: triangles counter-clockwise seen from +z (as slice_tet_mesh makes them). Returns the edges
// used by exactly one triangle, walked in the triangles' direction: outer loops counter-clockwise,
// holes clockwise, points as they are in the mesh. Where loops touch at a vertex, the walk keeps to
// the sector of the region it came along (the first boundary edge clockwise from the way back), and
// any loop that still meets itself is split there, so no loop repeats a vertex. Loops come in a
// deterministic order. Throws std::invalid_argument for a vertex index out of range or a
// boundary that does not close (triangles oriented inconsistently).
LayerOutline layer_outline(const LayerMesh& layer);

// Shoelace area of a closed loop [mm^2]: positive counter-clockwise, negative clockwise.
double signed_area(const Polygon& loop);

}  // namespace fibrecell::planner
