#pragma once
// The constant-strain (linear) tetrahedron for isotropic linear elasticity: shape-function
// gradients, stiffness blocks, stress and nodal internal forces.

#include "planner/fea/linear_elastic.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <array>

namespace fibrecell::planner {

// Lamé parameters [MPa] of an isotropic material.
struct Lame {
    double lambda;
    double mu;  // shear modulus G
};
Lame lame_parameters(const Material& material);

// Gradients of the four linear shape functions (constant over the tet) and its volume.
struct TetGeometry {
    std::array<Eigen::Vector3d, 4> grad;  // dN_a/dx [1/mm]
    double volume;                        // [mm^3], > 0 for a positively oriented tet
};
TetGeometry tet_geometry(const TetMesh& mesh, const Tet& tet);

// 3x3 block of the element stiffness coupling the displacement of vertex b (columns) into the
// force at vertex a (rows) [N/mm]: V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I).
Eigen::Matrix3d stiffness_block(const TetGeometry& g, const Lame& lame, int a, int b);

// Cauchy stress [MPa] of the constant strain given the four vertex displacements [mm].
StressTensor tet_stress(const TetGeometry& g, const Lame& lame,
                        const std::array<Eigen::Vector3d, 4>& u);

}  // namespace fibrecell::planner
