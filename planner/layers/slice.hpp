#pragma once
// Cutting the tet mesh with a horizontal plane: the polygon mesh T of the paper's Section 4.2, as a
// connected, conforming triangle mesh whose every triangle knows its source tet.

#include "planner/layers/layer_mesh.hpp"
#include "planner/layers/slice_index.hpp"
#include "planner/mesh/tet_mesh.hpp"
#include "planner/progress.hpp"

#include <span>
#include <vector>

namespace fibrecell::planner {

struct SliceOptions {
    // Vertices closer to the plane than this fraction of the mesh's bounding-box diagonal count as
    // on it, and section points closer than that to each other are merged [1].
    double snap_tolerance = 1e-9;
};

// mesh: positively oriented tets [mm]; z: plane height [mm]. Returns the cross-section at z:
// vertices shared between neighbouring tets (one per cut mesh edge or mesh vertex on the plane),
// triangles counter-clockwise seen from +z with positive area, triangle_tet their source tets. A
// plane through mesh vertices, edges or faces is handled as if it lay an infinitesimal step lower,
// so a plane at a vertex layer gives the section of the tets below it; a plane at or below the
// part's bottom gives an empty mesh. Throws std::invalid_argument for a non-finite z or option, a
// bad vertex index or a cut tet that is not positively oriented.
LayerMesh slice_tet_mesh(const TetMesh& mesh, const SliceIndex& index, double z,
                         const SliceOptions& options = {});

// The same without a prebuilt index: O(#T) per call; use the indexed form for many layers.
LayerMesh slice_tet_mesh(const TetMesh& mesh, double z, const SliceOptions& options = {});

// One section per height in `heights` [mm], in order; progress stage "slice".
std::vector<LayerMesh> slice_layers(const TetMesh& mesh, std::span<const double> heights,
                                    const SliceOptions& options = {},
                                    const StepControl& control = {});

}  // namespace fibrecell::planner
