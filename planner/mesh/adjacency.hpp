#pragma once
// Element connectivity of a tet mesh: face neighbours (for the MST graph of Section 4.1) and
// vertex-sharing neighbours (the set N_e of the incompatibility filter, Eq. 2).

#include "planner/mesh/tet_mesh.hpp"

#include <array>
#include <span>
#include <vector>

namespace fibrecell::planner {

// face_neighbours[t][f]: the tet across the face opposite local vertex f, or -1 on the boundary.
using FaceNeighbours = std::vector<std::array<int, 4>>;
FaceNeighbours face_neighbours(const TetMesh& mesh);

// Compressed adjacency lists: neighbours of node i are targets[offsets[i] .. offsets[i+1]).
struct CsrGraph {
    std::vector<int> offsets;  // #nodes + 1
    std::vector<int> targets;

    std::size_t node_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
    std::span<const int> neighbours(int i) const {
        return {targets.data() + offsets[i], targets.data() + offsets[i + 1]};
    }
};

// For each vertex, the tets that use it.
CsrGraph vertex_to_tets(const TetMesh& mesh);

// For each tet, every other tet that shares a vertex, an edge or a face with it (sorted).
CsrGraph vertex_sharing_neighbours(const TetMesh& mesh);

}  // namespace fibrecell::planner
