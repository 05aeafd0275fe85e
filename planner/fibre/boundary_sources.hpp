#pragma once
// Where a layer meets the boundary the user chose for boundary-conformal fibres (paper Section
// 4.4, Step 1): the outline vertices of the layer that lie on a selected face of the part.

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

// The vertices of `layer` (sliced from `placed`) on its outline whose outline edge was cut from
// a selected face: the heat sources of the layer's boundary distance. Ascending, no repeats.
std::vector<int> boundary_sources(const LayerMesh& layer, const SelectedFaces& faces);

}  // namespace fibrecell::planner
