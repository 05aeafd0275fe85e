#pragma once
// Where a layer meets the boundary the user chose for boundary-conformal fibres (paper Section
// 4.4, Step 1): the outline edges of the layer that lie on a selected face of the part.

#include "planner/layers/layer_mesh.hpp"
#include "planner/mesh/boundary.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <unordered_map>
#include <vector>

namespace fibrecell::planner {

// The selected boundary faces of the placed part, by the tet they belong to.
struct SelectedFaces {
    std::unordered_map<int, std::vector<std::array<Eigen::Vector3d, 3>>> by_tet;  // [mm]

    bool empty() const { return by_tet.empty(); }
};

// placed: the part on the bed; faces: boundary triangles of it (vertex indices of `placed`).
SelectedFaces selected_faces(const TetMesh& placed, const std::vector<BoundaryTriangle>& faces);

// The outline edges of `layer` (sliced from `placed`) cut from a selected face, as pairs of
// vertex indices of `layer` (smaller first), ascending: where the rings of boundary-conformal
// fibre follow the outline.
std::vector<std::array<int, 2>> selected_outline_edges(const LayerMesh& layer,
                                                       const SelectedFaces& faces);

}  // namespace fibrecell::planner
