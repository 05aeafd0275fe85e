// GCC 12 at -O2 and above reports a false null dereference inside Eigen's CHOLMOD view of the
// matrix (SparseRef), located in Eigen's headers; silence it for this file only.
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include "planner/fea/sparse_cholesky.hpp"

#include "planner/fea/fea_error.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>

#include <dlfcn.h>

#include <mutex>
#include <string>

namespace fibrecell::planner {
namespace {

// OpenBLAS (Debian's libblas.so.3 when libopenblas0-pthread is installed) spins its worker
// threads; on a busy 2-core machine that turned a 0.4 s Loop solve into 4-8 s, while one thread
// loses only ~10% when the machine is idle. The planner parallelises across layers instead.
// Looked up at run time so the reference BLAS still works.
void keep_blas_single_threaded() {
    static std::once_flag once;
    std::call_once(once, [] {
        using SetThreads = void (*)(int);
        if (auto set =
                reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
            set(1);
    });
}

// CHOLMOD's supernodal LL^T, opened up enough to read the diagonal of the factor.
class CholmodLlt : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
  public:
    CholmodLlt() { cholmod().print = 0; }  // failures are reported through FeaError instead

    // Calls visit(original DOF, pivot) for every pivot; an LL^T pivot is the squared L diagonal.
    template <typename Visit>
    void for_each_pivot(Visit visit) const {
        const cholmod_factor& l = *m_cholmodFactor;
        const auto* perm = static_cast<const int*>(l.Perm);
        const auto* x = static_cast<const double*>(l.x);
        if (l.is_super) {
            const auto* super = static_cast<const int*>(l.super);
            const auto* pi = static_cast<const int*>(l.pi);
            const auto* px = static_cast<const int*>(l.px);
            for (std::size_t s = 0; s < l.nsuper; ++s) {
                const int rows = pi[s + 1] - pi[s];  // supernode: dense rows x columns block
                for (int j = 0; j < super[s + 1] - super[s]; ++j) {
                    const double d = x[px[s] + j * rows + j];
                    visit(perm[super[s] + j], d * d);
                }
            }
        } else {
            const auto* p = static_cast<const int*>(l.p);
            for (std::size_t j = 0; j < l.n; ++j) visit(perm[j], x[p[j]] * x[p[j]]);
        }
    }
    int status() { return cholmod().status; }
    // Original DOF of the pivot where a failed factorisation stopped.
    int failed_dof() const {
        return static_cast<const int*>(m_cholmodFactor->Perm)[m_cholmodFactor->minor];
    }
};

using EigenLdlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;

}  // namespace

struct SparseCholesky::Backend {
    LinearSolver solver;
    double singular_pivot_ratio;
    CholmodLlt cholmod;
    EigenLdlt eigen;
};

SparseCholesky::SparseCholesky(LinearSolver solver, double singular_pivot_ratio)
    : backend_(std::make_unique<Backend>()) {
    backend_->solver = solver;
    backend_->singular_pivot_ratio = singular_pivot_ratio;
}

SparseCholesky::~SparseCholesky() = default;

std::optional<SingularPivot> SparseCholesky::factorise(const SparseMatrix& lower) {
    keep_blas_single_threaded();
    const Eigen::VectorXd diagonal = lower.diagonal();
    // Worst pivot relative to its own diagonal entry; a mechanism leaves one at rounding level.
    int worst_dof = -1;
    double worst_ratio = 1.0;
    auto visit = [&](int dof, double pivot) {
        const double ratio = pivot / diagonal[dof];
        if (!(ratio >= worst_ratio)) {  // also catches NaN
            worst_ratio = ratio;
            worst_dof = dof;
        }
    };

    if (backend_->solver == LinearSolver::cholmod_supernodal) {
        CholmodLlt& llt = backend_->cholmod;
        llt.compute(lower);
        if (llt.status() == CHOLMOD_OUT_OF_MEMORY)
            throw FeaError("out of memory in the factorisation of " + std::to_string(lower.rows()) +
                           " unknowns (CHOLMOD)");
        if (llt.status() < 0)
            throw FeaError("CHOLMOD failed with status " + std::to_string(llt.status()));
        if (llt.info() != Eigen::Success) return SingularPivot{llt.failed_dof(), 0.0};
        llt.for_each_pivot(visit);
    } else {
        EigenLdlt& ldlt = backend_->eigen;
        ldlt.compute(lower);
        if (ldlt.info() != Eigen::Success) return SingularPivot{-1, 0.0};
        const auto& to_pivot = ldlt.permutationP().indices();  // DOF j is pivot to_pivot[j]
        const Eigen::VectorXd& d = ldlt.vectorD();
        for (int j = 0; j < lower.cols(); ++j) visit(j, d[to_pivot[j]]);
    }
    if (worst_dof >= 0 && !(worst_ratio > backend_->singular_pivot_ratio))
        return SingularPivot{worst_dof, worst_ratio};
    return std::nullopt;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
    Eigen::VectorXd x;
    if (backend_->solver == LinearSolver::cholmod_supernodal) {
        x = backend_->cholmod.solve(rhs);
        if (backend_->cholmod.info() != Eigen::Success) throw FeaError("CHOLMOD solve failed");
    } else {
        x = backend_->eigen.solve(rhs);
    }
    if (!x.allFinite()) throw FeaError("the solution is not finite (singular stiffness?)");
    return x;
}

}  // namespace fibrecell::planner
