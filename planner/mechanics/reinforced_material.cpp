#include "planner/mechanics/reinforced_material.hpp"

#include "planner/fea/tet_element.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {
namespace {

void check(const FibreMaterial& f, const Material& matrix) {
    auto positive = [](double v, const char* what) {
        if (!(v > 0) || !std::isfinite(v))
            throw std::invalid_argument(std::string(what) + " must be positive and finite, got " +
                                        std::to_string(v));
    };
    positive(f.fibre_modulus_mpa, "the fibre modulus");
    positive(f.ribbon_width_mm, "the ribbon width");
    positive(f.ribbon_height_mm, "the ribbon height");
    if (!(f.fibre_volume_fraction > 0 && f.fibre_volume_fraction <= 1))
        throw std::invalid_argument("the ribbon's fibre volume fraction must lie in (0, 1], got " +
                                    std::to_string(f.fibre_volume_fraction));
    if (!(f.fibre_modulus_mpa > matrix.youngs_modulus_mpa))
        throw std::invalid_argument("the fibre modulus (" + std::to_string(f.fibre_modulus_mpa) +
                                    " MPa) must exceed the matrix's (" +
                                    std::to_string(matrix.youngs_modulus_mpa) + " MPa)");
}

}  // namespace

Reinforcement reinforcement(const TetMesh& mesh, const FibreContent& content,
                            const FibreMaterial& fibre, const Material& matrix) {
    check(fibre, matrix);
    const std::size_t tets = mesh.tet_count();
    if (content.length_mm.size() != tets)
        throw std::invalid_argument("fibre content for " +
                                    std::to_string(content.length_mm.size()) +
                                    " tets, the mesh has " + std::to_string(tets));
    Reinforcement r;
    r.fibre_fraction.assign(tets, 0.0);
    r.direction.assign(tets, Eigen::Vector3d::Zero());
    r.added.assign(tets, VoigtStiffness::Zero());
    const double section_mm2 = fibre.ribbon_width_mm * fibre.ribbon_height_mm;
    const double modulus_gain = fibre.fibre_modulus_mpa - matrix.youngs_modulus_mpa;
    for (std::size_t t = 0; t < tets; ++t) {
        const double length = content.length_mm[t];
        if (length <= 0) continue;
        const double volume = tet_geometry(mesh, mesh.tets[t]).volume;
        double ribbon = length * section_mm2 / volume;
        if (ribbon > 1) {
            ++r.saturated_tets;
            ribbon = 1;
        }
        const double v_f = fibre.fibre_volume_fraction * ribbon;
        r.fibre_fraction[t] = v_f;
        r.fibre_volume_mm3 += v_f * volume;
        r.added[t] = (v_f * modulus_gain / length) * content.orientation4[t];
        // The orientation tensor's main axis: the direction the fibre stress is read along.
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(content.tangents[t] / length);
        r.direction[t] = eig.eigenvectors().col(2).normalized();
        ++r.reinforced_tets;
    }
    return r;
}

}  // namespace fibrecell::planner
