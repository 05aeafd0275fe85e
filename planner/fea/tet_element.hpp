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

// Small strain (symmetric, tensor shear components) of the four vertex displacements [mm].
Eigen::Matrix3d tet_strain(const TetGeometry& g, const std::array<Eigen::Vector3d, 4>& u);

using VoigtVector = Eigen::Matrix<double, 6, 1>;  // in the order of VoigtStiffness

// The strain-displacement matrix B_a (6x3) of vertex a: Voigt strain = sum_a B_a u_a.
Eigen::Matrix<double, 6, 3> strain_displacement(const TetGeometry& g, int a);

// (xx, yy, zz, 2yz, 2xz, 2xy) of a strain tensor, and a Voigt stress back to its tensor.
VoigtVector voigt_strain(const Eigen::Matrix3d& strain);
StressTensor stress_tensor(const VoigtVector& stress);

// 3x3 block V B_a^T C B_b of an element stiffness C [N/mm], the same coupling as
// stiffness_block for an anisotropic material.
Eigen::Matrix3d stiffness_block(const TetGeometry& g, const VoigtStiffness& c, int a, int b);

}  // namespace fibrecell::planner
