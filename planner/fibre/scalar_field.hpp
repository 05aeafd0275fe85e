#pragma once
// The scalar field s of one layer (paper Section 4.2, Eq. 6): a piecewise-linear s whose
// gradient best matches u_f rotated by 90 degrees in the plane. Its isocurves then run along the
// tensile direction and lie closer together where |u| is larger: denser fibres where the stress
// is higher.

#include "planner/layers/layer_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fibrecell::planner {

// layer: #V vertices, #F triangles (CCW); u_f: #F target vectors (Eq. 5). Returns #V values of
// s minimising sum_f area_f |grad s_f - rot90(u_f)|^2. The minimiser is unique up to a constant
// per connected piece of the layer: the first vertex of each piece is pinned to 0.
// Throws std::invalid_argument on a degenerate (zero-area) triangle, naming it.
std::vector<double> scalar_field(const LayerMesh& layer, const std::vector<Eigen::Vector2d>& u_f);

// The piecewise-linear s (#V) minimising sum_f area_f |grad s_f - target_f|^2, with the first
// vertex of each connected piece pinned to 0. scalar_field() uses it.
std::vector<double> fit_gradient(const LayerMesh& layer,
                                 const std::vector<Eigen::Vector2d>& target);

// Gradient of the piecewise-linear field s on triangle f [units of s per mm].
Eigen::Vector2d triangle_gradient(const LayerMesh& layer, const std::vector<double>& s, int f);

}  // namespace fibrecell::planner
