#pragma once
// Per-element tensile direction v_e and maximal tensile stress sigma_e (paper Section 4.1).

#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace fibrecell::planner {

// Principal stresses of one tensor, sorted by absolute value (largest first), with unit directions.
struct PrincipalStress {
    Eigen::Vector3d values;  // sigma_1, sigma_2, sigma_3 [MPa], |sigma_1| >= |sigma_2| >= |sigma_3|
    Eigen::Matrix3d directions;  // column i is tau_i (unit length; sign arbitrary)
};

PrincipalStress principal_stress(const StressTensor& sigma);

// Which of the paper's three rules chose v_e.
enum class TensileRule : std::uint8_t {
    first_principal = 0,   // sigma_1 > 0: v_e = tau_1, sigma_e = sigma_1
    second_principal = 1,  // sigma_1 < 0 < sigma_2 and |sigma_1/sigma_2| < mu: tau_2, sigma_2
    no_tension = 2,        // otherwise: v_e = tau_1, sigma_e = no_tension_sigma
};

struct TensileFieldOptions {
    double mu = 3.0;                 // how much stronger compression may be than tension (rule 2)
    double no_tension_sigma = 1e-5;  // sigma_e where there is no useful tension [MPa]
};

struct TensileField {
    std::vector<Eigen::Vector3d> v_e;  // #T unit vectors
    std::vector<double> sigma_e;       // #T [MPa]
    std::vector<TensileRule> rule;     // #T
};

// stress: #T tensors [MPa]. Returns v_e, sigma_e and the rule used, per element.
TensileField tensile_field(const std::vector<StressTensor>& stress,
                           const TensileFieldOptions& options = {});

}  // namespace fibrecell::planner
