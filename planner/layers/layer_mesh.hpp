#pragma once
// One layer's cross-section of the part: the polygon mesh T of the paper's Section 4.2, as
// triangles that remember their source tet, and its outline.

#include <Eigen/Core>

#include <array>
#include <vector>

namespace fibrecell::planner {

// A closed loop of points [mm]; the last point is not repeated.
using Polygon = std::vector<Eigen::Vector2d>;

struct LayerMesh {
    double z = 0;                               // height of the cutting plane [mm]
    std::vector<Eigen::Vector2d> vertices;      // #V in-plane positions [mm]
    std::vector<std::array<int, 3>> triangles;  // #F counter-clockwise seen from +z
    std::vector<int> triangle_tet;              // #F the tet each triangle was cut from
};

// The region of a layer: outer loops counter-clockwise, holes clockwise (seen from +z).
struct LayerOutline {
    std::vector<Polygon> loops;
};

}  // namespace fibrecell::planner
