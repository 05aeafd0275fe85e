#pragma once
// How well a layer's fibres follow the stress (report.json `quality`): the stress-weighted mean
// |cos| between fibre tangents and the in-plane tensile direction, the correlation between
// local fibre density and sigma^p, and how much the fibres turn (the oscillation the paper's
// field processing removes, its Fig. 10). Computed the same way for every strategy, so the field-based
// paths and the contour-zigzag baseline can be compared.

#include "planner/layers/layer_mesh.hpp"
#include "planner/toolpaths/toolpath.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace fibrecell::planner {

// Sums over one or more layers; combine layers with +=.
struct FibreQualitySums {
    double weighted_cos = 0, weight = 0;  // sum sigma*len*|cos|, sum sigma*len
    // Per grid cell with material: fibre length per area [1/mm] and mean sigma^p.
    std::vector<double> density, stress_p;
    double turning_rad = 0, turned_length_mm = 0;  // absolute heading change along the paths

    FibreQualitySums& operator+=(const FibreQualitySums& o);
    double alignment() const { return weight > 0 ? weighted_cos / weight : 0.0; }
    double density_correlation() const;  // Pearson; 0 when undefined
    // Degrees of heading change per metre of fibre, measured on chords FibreQualityOptions::
    // turning_chord_mm long (so that vertex noise below the ribbon's scale does not count).
    double turning_deg_per_m() const;
};

struct FibreQualityOptions {
    double cell_mm = 5.0;  // grid cell for the density comparison
    double p = 1.0;        // density exponent of the job
    double turning_chord_mm = 2.0;
};

// layer: the cut the paths lie in; v_e, sigma_e, v_defined per tet (placed frame).
FibreQualitySums fibre_quality(const LayerMesh& layer, const std::vector<Toolpath>& paths,
                               const std::vector<Eigen::Vector3d>& v_e,
                               const std::vector<double>& sigma_e,
                               const std::vector<std::uint8_t>& v_defined,
                               const FibreQualityOptions& options = {});

}  // namespace fibrecell::planner
