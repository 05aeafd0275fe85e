#pragma once
// Linear-elastic static FEA on the planner's tet mesh: constant-strain (linear) tets, an isotropic
// material with an optional anisotropic stiffness added per tet (fibre reinforcement), clamped
// vertex regions and surface forces. Units are mm, N and MPa throughout.

#include "planner/mesh/boundary.hpp"
#include "planner/mesh/tet_mesh.hpp"
#include "planner/progress.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace fibrecell::planner {

struct Material {
    double youngs_modulus_mpa = 3500.0;  // E [MPa], PLA
    double poisson_ratio = 0.36;         // nu, in (-1, 0.5)
};

// Vertices whose three displacements are held at zero (a clamp, a pin).
struct FixedRegion {
    std::string name;
    std::vector<int> vertices;  // vertex indices; duplicates are harmless
};

// A total force spread over boundary triangles by area: a uniform traction on the region.
struct ForceRegion {
    std::string name;
    std::vector<BoundaryTriangle> triangles;
    Eigen::Vector3d total_force_n = Eigen::Vector3d::Zero();  // [N]
};

// An anisotropic stiffness in Voigt notation [MPa], symmetric: strains ordered
// (xx, yy, zz, 2yz, 2xz, 2xy) (engineering shears), stresses (xx, yy, zz, yz, xz, xy).
using VoigtStiffness = Eigen::Matrix<double, 6, 6>;

struct LoadCase {
    Material material;
    std::vector<FixedRegion> supports;
    std::vector<ForceRegion> loads;
    // Stiffness each tet adds to the material's (planner/mechanics: the fibres in it): empty for
    // the isotropic material alone, else one per tet.
    std::vector<VoigtStiffness> added_stiffness;
};

enum class LinearSolver {
    cholmod_supernodal,     // SuiteSparse CHOLMOD supernodal LL^T (the faster one)
    eigen_simplicial_ldlt,  // Eigen SimplicialLDLT with AMD ordering, no external library
};

struct FeaOptions {
    LinearSolver solver = LinearSolver::cholmod_supernodal;  // sparse Cholesky back end
    // A factorisation pivot below this fraction of its matrix diagonal means the stiffness is
    // singular (a mechanism the support checks cannot see, e.g. parts joined at one vertex).
    double singular_pivot_ratio = 1e-12;
};

// Wall-clock seconds per phase.
struct FeaTimings {
    double checks_s = 0;         // load case validation, connectivity
    double assembly_s = 0;       // DOF numbering, sparsity pattern, element stiffness scatter
    double factorisation_s = 0;  // symbolic analysis and numeric Cholesky
    double solve_s = 0;          // triangular solves
    double stress_s = 0;         // element stress, reactions
    double total_s = 0;
};

struct FeaResult {
    std::vector<StressTensor> stress;  // #T Cauchy stress per tet [MPa], added stiffness in
    std::vector<Eigen::Vector3d> displacement;  // #V displacement per vertex [mm]
    std::vector<Eigen::Vector3d> reaction;      // #V reaction force [N], nonzero only when fixed
    std::size_t dof_count = 0;                  // unknowns of the reduced system (free DOFs)
    std::size_t matrix_nonzeros = 0;            // stored (lower triangle) stiffness entries
    std::string solver;                         // back end that ran, for logs
    double compliance_nmm = 0;                  // f·u, twice the strain energy [N mm]
    FeaTimings timings;
};

// Solves K u = f with the supports eliminated and returns per-tet stress, per-vertex displacement
// and reactions (K u - f at the fixed vertices). Vertices no tet uses are ignored (zero
// displacement). Throws FeaError for a set-up that has no unique solution or bad input, and
// Cancelled when `control` asks. Reports stage "fea".
FeaResult solve_linear_elastic(const TetMesh& mesh, const LoadCase& load_case,
                               const FeaOptions& options = {}, const StepControl& control = {});

// Human-readable name of a solver back end ("cholmod_supernodal", ...).
const char* solver_name(LinearSolver solver);

}  // namespace fibrecell::planner
