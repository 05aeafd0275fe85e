#pragma once
// Global stiffness of the free DOFs, assembled straight into a compressed lower-triangular
// pattern (no triplet list: a 100k-tet mesh would need ~10^7 of them).

#include "planner/fea/load_case_check.hpp"
#include "planner/fea/tet_element.hpp"

#include <Eigen/SparseCore>

#include <span>
#include <vector>

namespace fibrecell::planner {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Free vertices numbered 0..free_count-1 in vertex order; the DOFs of free vertex f are
// 3f + {0, 1, 2} for x, y, z. Fixed and unused vertices have no DOFs.
struct DofNumbering {
    std::vector<int> free_index;  // #V, -1 for fixed or unused vertices
    int free_count = 0;
    int dof_count() const { return 3 * free_count; }
};
DofNumbering number_free_dofs(const VertexRoles& roles);

// Lower triangle (row >= column) of the reduced stiffness, (3 free_count)^2 [N/mm], compressed.
// `added`: empty, or per tet a stiffness added to the isotropic one (LoadCase::added_stiffness).
SparseMatrix assemble_stiffness(const TetMesh& mesh, const Lame& lame, const DofNumbering& dofs,
                                std::span<const VoigtStiffness> added = {});

}  // namespace fibrecell::planner
