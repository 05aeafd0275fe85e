#pragma once
// MST-based re-orientation of the tensile direction field (paper Section 4.1, after Hoppe 92).
// Eigenvectors have an arbitrary sign; propagating a sign along a minimum spanning tree of the
// face-adjacency graph, weighted w_ij = 1 - |v_i.v_j| (Eq. 1), keeps the propagation away from
// regions where the direction turns sharply.

#include "planner/mesh/adjacency.hpp"
#include "planner/progress.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

struct MstReorientationResult {
    std::vector<int> parent;  // #T tree parent, -1 for the seed of each connected component
    int components = 0;       // connected components of the face-adjacency graph
    int flipped = 0;          // vectors whose sign was reversed
};

// Flips vectors of `v_e` (#T unit vectors, in place) so that each agrees with its tree parent.
// Each component is seeded at its element of largest sigma_e (#T), the most trustworthy direction.
// Prim's algorithm grows the tree and orients each element the moment it joins, so building the
// tree and propagating the signs are one pass: O(E log E).
MstReorientationResult mst_reorient(std::vector<Eigen::Vector3d>& v_e,
                                    const std::vector<double>& sigma_e,
                                    const FaceNeighbours& neighbours,
                                    const StepControl& control = {});

}  // namespace fibrecell::planner
