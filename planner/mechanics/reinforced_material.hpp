#pragma once
// The printed part as a material: PLA everywhere, and in each tet the CCF it holds as a smeared
// 1-D reinforcement along its paths (docs/mechanics.md). A ribbon of fibre volume fraction phi
// makes a tet of ribbon volume fraction v_r carry, along a path direction t, the extra stress
// v_f (E_f - E_m) (t.eps.t) t t^T with v_f = phi v_r: along straight aligned fibre that is the
// rule of mixtures, E = v_f E_f + (1 - v_f) E_m, exactly; across them the matrix alone.

#include "planner/fea/linear_elastic.hpp"
#include "planner/mechanics/fibre_content.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

// Published defaults (docs/mechanics.md): a T300-class carbon fibre, and the fibre fraction
// that makes the ribbon's rule-of-mixtures modulus 60 GPa, what commercial continuous carbon
// filament is specified at.
struct FibreMaterial {
    double fibre_modulus_mpa = 230000.0;  // E_f, along the fibre
    double fibre_volume_fraction = 0.25;  // phi, of the ribbon's section
    double ribbon_width_mm = 1.2;         // the CCF line width (job process.ccf.line_width_mm)
    double ribbon_height_mm = 0.05;       // the CCF layer height (job layers.ccf_layer_height_mm)
};

struct Reinforcement {
    std::vector<double> fibre_fraction;      // #T v_f: fibre volume over tet volume
    std::vector<Eigen::Vector3d> direction;  // #T main fibre direction (unit; zero: no fibre)
    std::vector<VoigtStiffness> added;       // #T stiffness the fibre adds [MPa] (LoadCase)
    int reinforced_tets = 0;                 // tets with fibre in them
    int saturated_tets = 0;                  // tets whose ribbons would overfill them (v_r > 1)
    double fibre_volume_mm3 = 0;             // fibre (not ribbon) volume in the part
};

// The fibre of `content` in `mesh` (the model frame). A ribbon fraction above 1 (paths packed
// tighter than a tet can hold) is taken as 1 and counted in saturated_tets. Throws
// std::invalid_argument for a non-positive or non-finite modulus, ribbon size or a fraction
// outside (0, 1].
Reinforcement reinforcement(const TetMesh& mesh, const FibreContent& content,
                            const FibreMaterial& fibre, const Material& matrix);

}  // namespace fibrecell::planner
