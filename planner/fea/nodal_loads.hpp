#pragma once
// Turns region forces into vertex forces: each region's total force is spread over its triangles
// by area (a uniform traction), one third of a triangle's share to each of its vertices, which
// is the consistent load of a linear triangle.

#include "planner/fea/linear_elastic.hpp"

#include <vector>

namespace fibrecell::planner {

// #V vertex forces [N] summed over all regions. Regions must have positive area.
std::vector<Eigen::Vector3d> nodal_forces(const TetMesh& mesh,
                                          const std::vector<ForceRegion>& loads);

}  // namespace fibrecell::planner
