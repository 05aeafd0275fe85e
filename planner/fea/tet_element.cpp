#include "planner/fea/tet_element.hpp"

#include <Eigen/LU>  // 3x3 inverse and determinant

namespace fibrecell::planner {

Lame lame_parameters(const Material& material) {
    const double e = material.youngs_modulus_mpa;
    const double nu = material.poisson_ratio;
    return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

TetGeometry tet_geometry(const TetMesh& mesh, const Tet& tet) {
    const Eigen::Vector3d& x0 = mesh.vertices[tet[0]];
    Eigen::Matrix3d edges;  // columns x_a - x_0, a = 1..3
    for (int a = 1; a < 4; ++a) edges.col(a - 1) = mesh.vertices[tet[a]] - x0;
    // N_a(x) = (E^-1 (x - x0))_a for a = 1..3, so grad N_a is row a-1 of E^-1.
    const Eigen::Matrix3d inv = edges.inverse();
    TetGeometry g;
    for (int a = 1; a < 4; ++a) g.grad[a] = inv.row(a - 1).transpose();
    g.grad[0] = -(g.grad[1] + g.grad[2] + g.grad[3]);
    g.volume = edges.determinant() / 6.0;
    return g;
}

Eigen::Matrix3d stiffness_block(const TetGeometry& g, const Lame& lame, int a, int b) {
    const Eigen::Vector3d& ga = g.grad[a];
    const Eigen::Vector3d& gb = g.grad[b];
    Eigen::Matrix3d k = lame.lambda * ga * gb.transpose() + lame.mu * gb * ga.transpose();
    k.diagonal().array() += lame.mu * ga.dot(gb);
    return g.volume * k;
}

Eigen::Matrix3d tet_strain(const TetGeometry& g, const std::array<Eigen::Vector3d, 4>& u) {
    Eigen::Matrix3d grad_u = Eigen::Matrix3d::Zero();  // (i, j) = du_i/dx_j
    for (int a = 0; a < 4; ++a) grad_u += u[a] * g.grad[a].transpose();
    return 0.5 * (grad_u + grad_u.transpose());
}

StressTensor tet_stress(const TetGeometry& g, const Lame& lame,
                        const std::array<Eigen::Vector3d, 4>& u) {
    const Eigen::Matrix3d strain = tet_strain(g, u);
    StressTensor s = 2 * lame.mu * strain;
    s.diagonal().array() += lame.lambda * strain.trace();
    return s;
}

Eigen::Matrix<double, 6, 3> strain_displacement(const TetGeometry& g, int a) {
    const Eigen::Vector3d& d = g.grad[a];
    Eigen::Matrix<double, 6, 3> b;
    // clang-format off
    b << d.x(), 0,     0,
         0,     d.y(), 0,
         0,     0,     d.z(),
         0,     d.z(), d.y(),
         d.z(), 0,     d.x(),
         d.y(), d.x(), 0;
    // clang-format on
    return b;
}

VoigtVector voigt_strain(const Eigen::Matrix3d& e) {
    VoigtVector v;
    v << e(0, 0), e(1, 1), e(2, 2), 2 * e(1, 2), 2 * e(0, 2), 2 * e(0, 1);
    return v;
}

StressTensor stress_tensor(const VoigtVector& s) {
    StressTensor t;
    // clang-format off
    t << s[0], s[5], s[4],
         s[5], s[1], s[3],
         s[4], s[3], s[2];
    // clang-format on
    return t;
}

Eigen::Matrix3d stiffness_block(const TetGeometry& g, const VoigtStiffness& c, int a, int b) {
    return g.volume * (strain_displacement(g, a).transpose() * c * strain_displacement(g, b));
}

}  // namespace fibrecell::planner
