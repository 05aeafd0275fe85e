#pragma once
// How the part sits on the bed (job `placement`): a rotation about x, then y, then z, then a shift
// that puts the lowest point on the bed (z = 0) and the bounding-box centre at position_mm.

#include "planner/job/job_spec.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace fibrecell::planner {

// p_bed = rotation * p_model + translation.
struct Placement {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // R = Rz * Ry * Rx
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();   // [mm]

    Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return rotation * p + translation; }
};

// mesh: the part in its own frame [mm]. Throws std::invalid_argument for a mesh without vertices
// or a non-finite spec.
Placement placement_for(const TetMesh& mesh, const PlacementSpec& spec);

// The mesh with every vertex moved onto the bed; tets are unchanged (a rotation keeps their
// orientation).
TetMesh place_mesh(const TetMesh& mesh, const Placement& placement);

// Per-element directions (v_e, #T) turned with the part: R v_e. Lengths are kept.
std::vector<Eigen::Vector3d> rotate_vectors(std::span<const Eigen::Vector3d> vectors,
                                            const Placement& placement);

// Height of a part [mm]: its extent in z (for a placed part, the highest vertex z). Throws
// std::invalid_argument for a mesh without vertices.
double part_height(const TetMesh& placed);

}  // namespace fibrecell::planner
