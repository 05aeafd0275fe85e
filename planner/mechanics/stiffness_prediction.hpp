#pragma once
// What the fibres buy: the job's load case solved for the bare part and again with the
// reinforcement, and the figures an engineer compares (docs/mechanics.md).

#include "planner/fea/linear_elastic.hpp"
#include "planner/mechanics/reinforced_material.hpp"
#include "planner/progress.hpp"

#include <optional>
#include <span>
#include <vector>

namespace fibrecell::planner {

struct PartResponse {
    // Force over displacement along the load: (sum |F_i|)^2 / sum (u . f_i), f_i the nodal
    // forces of load i. For one load that is |F| over the load-weighted mean displacement of its
    // region along F (the displacement the load does work on).
    double stiffness_n_per_mm = 0;
    double displacement_mm = 0;        // that mean displacement, sum (u . f_i) / sum |F_i|
    double von_mises_peak_mpa = 0;     // matrix (PLA) stress, over all tets
    double von_mises_p99_mpa = 0;      // its 99th percentile over the tets
    double fibre_stress_peak_mpa = 0;  // E_f times the strain along the fibre, the largest
                                       // tension over reinforced tets (0 without fibre)
    FeaTimings fea;                    // of its solve (zeros when it was the field stage's)
};

// A solve already made of the bare part (the field stage's, for the job's own load case).
struct BareSolution {
    std::span<const Eigen::Vector3d> displacement;  // #V [mm]
    std::span<const StressTensor> stress;           // #T [MPa]
};

struct StiffnessPrediction {
    PartResponse bare, reinforced;
    std::vector<double> reinforced_von_mises;  // #T matrix von Mises with the fibre [MPa]

    double gain() const {
        return bare.stiffness_n_per_mm > 0 ? reinforced.stiffness_n_per_mm / bare.stiffness_n_per_mm
                                           : 0;
    }
};

// The response of one solved load case; `fibre` null for the bare part (with fibre, the matrix
// stress is the PLA's share, from the strain, not the smeared total). `matrix_von_mises`, when
// given, receives the matrix von Mises stress per tet [MPa].
PartResponse part_response(const TetMesh& mesh, const LoadCase& load_case,
                           const BareSolution& solved, const Reinforcement* fibre,
                           double fibre_modulus_mpa,
                           std::vector<double>* matrix_von_mises = nullptr);

// Solves `load_case` (its added_stiffness must be empty) reinforced, and bare unless `bare`
// gives that solve already. Progress goes to ("mechanics", fraction). Throws FeaError for a load
// case the FEA refuses, std::invalid_argument for a bare solution of another mesh, Cancelled.
StiffnessPrediction predict_stiffness(const TetMesh& mesh, const LoadCase& load_case,
                                      const Reinforcement& fibre, double fibre_modulus_mpa,
                                      const StepControl& control = {},
                                      std::optional<BareSolution> bare = std::nullopt);

}  // namespace fibrecell::planner
