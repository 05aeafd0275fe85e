#pragma once
// Sparse Cholesky of the symmetric positive definite stiffness, behind one interface so the
// back end (CHOLMOD or Eigen's simplicial LDL^T) is an option and CHOLMOD stays private.

#include "planner/fea/linear_elastic.hpp"
#include "planner/fea/stiffness_assembly.hpp"

#include <Eigen/Core>

#include <memory>
#include <optional>

namespace fibrecell::planner {

// Where a factorisation found the matrix singular.
struct SingularPivot {
    int dof = -1;            // original DOF of the failed pivot, -1 when the back end cannot say
    double pivot_ratio = 0;  // pivot over its matrix diagonal entry (0 when it was not positive)
};

class SparseCholesky {
  public:
    // Pivots below singular_pivot_ratio times their matrix diagonal count as singular.
    SparseCholesky(LinearSolver solver, double singular_pivot_ratio);
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    // Orders and factorises the lower triangle `lower`; returns the worst pivot when the matrix
    // is not (numerically) positive definite. Throws FeaError when the back end itself fails.
    std::optional<SingularPivot> factorise(const SparseMatrix& lower);

    // x with K x = rhs; factorise() must have succeeded. Throws FeaError on a solver failure.
    Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  private:
    struct Backend;
    std::unique_ptr<Backend> backend_;
};

}  // namespace fibrecell::planner
