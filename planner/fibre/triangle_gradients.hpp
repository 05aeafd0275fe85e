#pragma once
// Piecewise-linear calculus on a layer mesh: the constant gradients of the three hat functions of
// a triangle, used by the least-squares fit of the scalar field.

#include "planner/layers/layer_mesh.hpp"

#include <Eigen/Core>

#include <array>

namespace fibrecell::planner {

struct TriangleGradients {
    double area;                          // [mm^2]
    std::array<Eigen::Vector2d, 3> grad;  // gradient of the hat function of each corner [1/mm]
};

// Throws std::invalid_argument for a triangle without positive area, naming it and the layer.
TriangleGradients triangle_gradients(const LayerMesh& layer, int f);

}  // namespace fibrecell::planner
