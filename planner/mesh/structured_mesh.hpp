#pragma once
// Structured tet meshes of boxes, optionally with cells cut away: analytic test cases and
// benchmark parts of a chosen size, without a mesher.

#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>

namespace fibrecell::planner {

struct StructuredMeshOptions {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // min corner [mm]
    Eigen::Vector3d size = Eigen::Vector3d::Ones();    // box extent [mm]
    std::array<int, 3> cells = {1, 1, 1};              // hexahedral cells per axis
    // Keeps a cell when it returns true for the cell centre [mm]; empty keeps all.
    std::function<bool(const Eigen::Vector3d&)> keep_cell;
};

// Splits every kept cell into 6 tets around its main diagonal (Kuhn), which makes neighbouring
// cells conforming; vertices no kept cell uses are dropped. 6 * kept cells tets, all positive.
TetMesh structured_tet_mesh(const StructuredMeshOptions& options);

}  // namespace fibrecell::planner
