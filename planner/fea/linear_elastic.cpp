#include "planner/fea/linear_elastic.hpp"

#include "planner/fea/fea_error.hpp"
#include "planner/fea/load_case_check.hpp"
#include "planner/fea/nodal_loads.hpp"
#include "planner/fea/sparse_cholesky.hpp"
#include "planner/fea/stiffness_assembly.hpp"
#include "planner/fea/tet_element.hpp"
#include "planner/stopwatch.hpp"

#include <sstream>

namespace fibrecell::planner {
namespace {

constexpr const char* kStage = "fea";

[[noreturn]] void throw_singular(const TetMesh& mesh, const DofNumbering& dofs,
                                 const SingularPivot& pivot) {
    std::ostringstream where;
    where.precision(3);
    if (pivot.pivot_ratio > 0)
        where << "pivot " << pivot.pivot_ratio << " of its diagonal";
    else
        where << "non-positive pivot";
    if (pivot.dof >= 0) {
        int vertex = 0;
        while (dofs.free_index[vertex] != pivot.dof / 3) ++vertex;
        const Eigen::Vector3d& p = mesh.vertices[vertex];
        where << " at the "
              << "xyz"[pivot.dof % 3] << " displacement of vertex " << vertex << " [" << p.x()
              << ", " << p.y() << ", " << p.z() << "]";
    }
    throw FeaError("the stiffness matrix is singular (" + where.str() +
                   "): part of the mesh can still move, e.g. pieces joined only at a vertex "
                   "or an edge");
}

// Scatters the free-DOF solution back to all vertices; fixed and unused ones stay at zero.
std::vector<Eigen::Vector3d> vertex_displacements(const DofNumbering& dofs,
                                                  const Eigen::VectorXd& x) {
    std::vector<Eigen::Vector3d> u(dofs.free_index.size(), Eigen::Vector3d::Zero());
    for (std::size_t v = 0; v < u.size(); ++v)
        if (const int f = dofs.free_index[v]; f >= 0) u[v] = x.segment<3>(3 * f);
    return u;
}

// Element stresses, and reactions as the internal force K u (sum of V sigma grad N_a) minus
// the applied force at the fixed vertices.
void stresses_and_reactions(const TetMesh& mesh, const Lame& lame,
                            const std::vector<VoigtStiffness>& added, const VertexRoles& roles,
                            const std::vector<Eigen::Vector3d>& applied, FeaResult& r) {
    std::vector<Eigen::Vector3d> internal(mesh.vertex_count(), Eigen::Vector3d::Zero());
    r.stress.resize(mesh.tet_count());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        const Tet& tet = mesh.tets[t];
        const TetGeometry g = tet_geometry(mesh, tet);
        const std::array<Eigen::Vector3d, 4> u = {r.displacement[tet[0]], r.displacement[tet[1]],
                                                  r.displacement[tet[2]], r.displacement[tet[3]]};
        r.stress[t] = tet_stress(g, lame, u);
        if (!added.empty() && !added[t].isZero())
            r.stress[t] += stress_tensor(added[t] * voigt_strain(tet_strain(g, u)));
        for (int a = 0; a < 4; ++a) internal[tet[a]] += g.volume * (r.stress[t] * g.grad[a]);
    }
    r.reaction.assign(mesh.vertex_count(), Eigen::Vector3d::Zero());
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        if (roles.fixed[v]) r.reaction[v] = internal[v] - applied[v];
}

}  // namespace

const char* solver_name(LinearSolver solver) {
    switch (solver) {
        case LinearSolver::cholmod_supernodal:
            return "cholmod_supernodal";
        case LinearSolver::eigen_simplicial_ldlt:
            return "eigen_simplicial_ldlt";
    }
    return "unknown";
}

FeaResult solve_linear_elastic(const TetMesh& mesh, const LoadCase& load_case,
                               const FeaOptions& options, const StepControl& control) {
    Stopwatch total;
    Stopwatch phase;
    FeaResult r;
    r.solver = solver_name(options.solver);
    control.report(kStage, 0.0);

    const VertexRoles roles = check_load_case(mesh, load_case);
    const Lame lame = lame_parameters(load_case.material);
    r.timings.checks_s = phase.lap();
    control.check_cancel();
    control.report(kStage, 0.05);

    const DofNumbering dofs = number_free_dofs(roles);
    const SparseMatrix k = assemble_stiffness(mesh, lame, dofs, load_case.added_stiffness);
    const std::vector<Eigen::Vector3d> applied = nodal_forces(mesh, load_case.loads);
    Eigen::VectorXd rhs(dofs.dof_count());
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        if (const int f = dofs.free_index[v]; f >= 0) rhs.segment<3>(3 * f) = applied[v];
    r.dof_count = static_cast<std::size_t>(dofs.dof_count());
    r.matrix_nonzeros = static_cast<std::size_t>(k.nonZeros());
    r.timings.assembly_s = phase.lap();
    control.check_cancel();
    control.report(kStage, 0.2);

    Eigen::VectorXd x = Eigen::VectorXd::Zero(dofs.dof_count());
    if (dofs.dof_count() > 0) {  // all vertices fixed: nothing moves
        SparseCholesky cholesky(options.solver, options.singular_pivot_ratio);
        if (const auto singular = cholesky.factorise(k)) throw_singular(mesh, dofs, *singular);
        r.timings.factorisation_s = phase.lap();
        control.check_cancel();
        control.report(kStage, 0.8);
        x = cholesky.solve(rhs);
    }
    r.displacement = vertex_displacements(dofs, x);
    r.compliance_nmm = rhs.dot(x);
    r.timings.solve_s = phase.lap();
    control.check_cancel();
    control.report(kStage, 0.9);

    stresses_and_reactions(mesh, lame, load_case.added_stiffness, roles, applied, r);
    r.timings.stress_s = phase.lap();
    r.timings.total_s = total.lap();
    control.report(kStage, 1.0);
    return r;
}

}  // namespace fibrecell::planner
