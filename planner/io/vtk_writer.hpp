#pragma once
// Writes a tet mesh with per-element fields as a legacy VTK unstructured grid, for ParaView.

#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace fibrecell::planner {

struct FieldArrays {
    const std::vector<StressTensor>* stress = nullptr;     // #T [MPa] -> TENSORS "stress"
    const std::vector<double>* sigma_e = nullptr;          // #T [MPa] -> SCALARS "sigma_e"
    const std::vector<Eigen::Vector3d>* v_e = nullptr;     // #T unit  -> VECTORS "v_e"
    const std::vector<std::uint8_t>* v_defined = nullptr;  // #T 0/1   -> SCALARS "v_defined" int
};

enum class VtkEncoding { binary, ascii };

// `mesh` with the given per-element arrays (null ones are left out) as a VTK file's bytes; binary
// by default (a third of the size, exact doubles).
std::string field_vtk_text(const TetMesh& mesh, const FieldArrays& arrays,
                           VtkEncoding encoding = VtkEncoding::binary);

}  // namespace fibrecell::planner
