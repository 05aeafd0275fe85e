#include "planner/field/tensile_field.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace fibrecell::planner {

PrincipalStress principal_stress(const StressTensor& sigma) {
    // Closed-form 3x3 solver: an order of magnitude faster than the iterative one and accurate
    // enough for directions (checked against it in the tests).
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(sigma);
    const Eigen::Vector3d& values = solver.eigenvalues();
    std::array<int, 3> order = {0, 1, 2};
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return std::abs(values[a]) > std::abs(values[b]); });
    PrincipalStress p;
    for (int i = 0; i < 3; ++i) {
        p.values[i] = values[order[i]];
        p.directions.col(i) = solver.eigenvectors().col(order[i]).normalized();
    }
    return p;
}

TensileField tensile_field(const std::vector<StressTensor>& stress,
                           const TensileFieldOptions& options) {
    TensileField field;
    field.v_e.resize(stress.size());
    field.sigma_e.resize(stress.size());
    field.rule.resize(stress.size());
    for (std::size_t e = 0; e < stress.size(); ++e) {
        const PrincipalStress p = principal_stress(stress[e]);
        const double s1 = p.values[0];
        const double s2 = p.values[1];
        if (s1 > 0.0) {
            field.v_e[e] = p.directions.col(0);
            field.sigma_e[e] = s1;
            field.rule[e] = TensileRule::first_principal;
        } else if (s1 < 0.0 && s2 > 0.0 && std::abs(s1 / s2) < options.mu) {
            field.v_e[e] = p.directions.col(1);
            field.sigma_e[e] = s2;
            field.rule[e] = TensileRule::second_principal;
        } else {
            field.v_e[e] = p.directions.col(0);
            field.sigma_e[e] = options.no_tension_sigma;
            field.rule[e] = TensileRule::no_tension;
        }
    }
    return field;
}

}  // namespace fibrecell::planner
