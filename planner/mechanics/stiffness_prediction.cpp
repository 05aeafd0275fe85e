#include "planner/mechanics/stiffness_prediction.hpp"

#include "planner/fea/nodal_loads.hpp"
#include "planner/fea/tet_element.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace fibrecell::planner {
namespace {

constexpr const char* kStage = "mechanics";

double von_mises(const StressTensor& s) {
    const Eigen::Matrix3d dev = s - (s.trace() / 3.0) * Eigen::Matrix3d::Identity();
    return std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
}

double percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0;
    const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
    return values[k];
}

}  // namespace

PartResponse part_response(const TetMesh& mesh, const LoadCase& load_case,
                           const BareSolution& solved, const Reinforcement* fibre,
                           double fibre_modulus_mpa, std::vector<double>* matrix_von_mises) {
    PartResponse r;
    const auto& u_all = solved.displacement;
    double force = 0, work = 0;
    for (const ForceRegion& load : load_case.loads) {
        const std::vector<Eigen::Vector3d> f = nodal_forces(mesh, {load});
        for (std::size_t v = 0; v < f.size(); ++v) work += u_all[v].dot(f[v]);
        force += load.total_force_n.norm();
    }
    if (force > 0) r.displacement_mm = work / force;
    if (work > 0) r.stiffness_n_per_mm = force * force / work;

    const Lame lame = lame_parameters(load_case.material);
    std::vector<double> matrix(mesh.tet_count());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        const Tet& tet = mesh.tets[t];
        if (!fibre) {
            matrix[t] = von_mises(solved.stress[t]);
            continue;
        }
        const TetGeometry g = tet_geometry(mesh, tet);
        const std::array<Eigen::Vector3d, 4> u = {u_all[tet[0]], u_all[tet[1]], u_all[tet[2]],
                                                  u_all[tet[3]]};
        matrix[t] = von_mises(tet_stress(g, lame, u));
        if (fibre->fibre_fraction[t] > 0) {
            const Eigen::Vector3d& d = fibre->direction[t];
            const double along = d.dot(tet_strain(g, u) * d);
            r.fibre_stress_peak_mpa = std::max(r.fibre_stress_peak_mpa, fibre_modulus_mpa * along);
        }
    }
    r.von_mises_peak_mpa = matrix.empty() ? 0 : *std::max_element(matrix.begin(), matrix.end());
    r.von_mises_p99_mpa = percentile(matrix, 0.99);
    if (matrix_von_mises) *matrix_von_mises = std::move(matrix);
    return r;
}

StiffnessPrediction predict_stiffness(const TetMesh& mesh, const LoadCase& load_case,
                                      const Reinforcement& fibre, double fibre_modulus_mpa,
                                      const StepControl& control,
                                      std::optional<BareSolution> bare) {
    if (!load_case.added_stiffness.empty())
        throw std::invalid_argument(
            "predict_stiffness: the load case already has an added "
            "stiffness; give the bare part's");
    if (bare && (bare->displacement.size() != mesh.vertex_count() ||
                 bare->stress.size() != mesh.tet_count()))
        throw std::invalid_argument("predict_stiffness: the bare solution is of another mesh");
    // Each solve reports its own "fea" progress; here it is its share of "mechanics".
    const double bare_share = bare ? 0.0 : 0.5;
    auto part = [&](double from, double share) {
        return StepControl{[&control, from, share](std::string_view, double f) {
                               control.report(kStage, from + share * f);
                           },
                           control.cancel};
    };
    StiffnessPrediction p;
    control.report(kStage, 0.0);
    if (bare) {
        p.bare = part_response(mesh, load_case, *bare, nullptr, fibre_modulus_mpa);
    } else {
        const FeaResult solved = solve_linear_elastic(mesh, load_case, {}, part(0.0, bare_share));
        p.bare = part_response(mesh, load_case, {solved.displacement, solved.stress}, nullptr,
                               fibre_modulus_mpa);
        p.bare.fea = solved.timings;
    }

    LoadCase reinforced = load_case;
    reinforced.added_stiffness = fibre.added;
    const FeaResult with =
        solve_linear_elastic(mesh, reinforced, {}, part(bare_share, 1.0 - bare_share));
    p.reinforced = part_response(mesh, reinforced, {with.displacement, with.stress}, &fibre,
                                 fibre_modulus_mpa, &p.reinforced_von_mises);
    p.reinforced.fea = with.timings;
    control.report(kStage, 1.0);
    return p;
}

}  // namespace fibrecell::planner
