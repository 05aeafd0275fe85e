#pragma once
// Connected parts of a tet mesh (tets that share a vertex belong to one part): each part needs
// its own supports, or it floats.

#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace fibrecell::planner {

struct MeshParts {
    std::vector<int> part_of_vertex;  // #V part index, -1 for vertices no tet uses
    int count = 0;                    // number of parts, numbered by their lowest vertex
};

MeshParts mesh_parts(const TetMesh& mesh);

// Axis-aligned bounding box [mm].
struct Box {
    Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
    void add(const Eigen::Vector3d& p) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
};

}  // namespace fibrecell::planner
