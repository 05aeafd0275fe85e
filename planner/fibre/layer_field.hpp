#pragma once
// The in-plane field of one layer (paper Section 4.2, Eq. 3-5): each triangle of the layer mesh T
// takes its tet's tensile direction projected into the plane and its sigma_e; undefined
// directions are filled and all values smoothed by a local Laplacian; then
// u_f = sigma_f^p v_f / |v_f|.

#include "planner/layers/layer_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace fibrecell::planner {

struct LayerFieldOptions {
    int smoothing_iterations = 50;  // Jacobi sweeps of the local Laplacian (paper: converges in 50)
    double p = 1.0;                 // density exponent of Eq. 5 (0: uniform spacing)
    // A projected direction shorter than this (a tet whose v_e is nearly vertical) carries no
    // in-plane information and is treated as undefined.
    double min_projected_length = 0.2;
    // Caps sigma_f at this percentile of the layer's values before Eq. 5 (100 = no cap). A stress
    // singularity (the edge of a clamp, a re-entrant corner) otherwise sets the minimal spacing
    // for the whole layer and thins the fibres everywhere else.
    double sigma_cap_percentile = 100.0;
};

struct LayerField {
    std::vector<Eigen::Vector2d> v_f;   // #F smoothed in-plane direction (not normalised)
    std::vector<double> sigma_f;        // #F smoothed tensile stress [MPa]
    std::vector<Eigen::Vector2d> u_f;   // #F sigma_f^p v_f/|v_f| (Eq. 5); zero where unknown
    std::vector<std::uint8_t> defined;  // #F 1 where the face had a usable direction before filling
    int fixed_face = -1;                // the face of maximal sigma, held fixed while smoothing
};

// Face neighbours of a triangle mesh: for triangle f, the triangles sharing an edge with it.
std::vector<std::vector<int>> triangle_neighbours(const LayerMesh& layer);

// layer: the cut of the placed tet mesh; v_e, sigma_e, v_defined: per tet (#T), v_e already
// rotated into the placed frame. Returns the per-face field.
LayerField layer_field(const LayerMesh& layer, const std::vector<Eigen::Vector3d>& v_e,
                       const std::vector<double>& sigma_e,
                       const std::vector<std::uint8_t>& v_defined,
                       const LayerFieldOptions& options = {});

}  // namespace fibrecell::planner
