#pragma once
// Regions select parts of the model's boundary for supports, loads and boundary-conformal fibres.
// A region is a geometric selector (box, cylinder shell) or a named vertex group from the mesh
// file; a boundary triangle belongs to a region when all three of its vertices lie inside it.

#include "planner/mesh/boundary.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <variant>
#include <vector>

namespace fibrecell::planner {

struct BoxRegion {
    Eigen::Vector3d min;  // [mm], inclusive
    Eigen::Vector3d max;
};

// Points whose distance from the axis line is radius_mm +- tolerance_mm: the surface of a pin
// hole or a round outline, without the flat faces that meet it.
struct CylinderRegion {
    Eigen::Vector3d point;  // any point on the axis [mm]
    Eigen::Vector3d axis;   // axis direction (normalised on load)
    double radius_mm = 0;
    double tolerance_mm = 0;
    // Unit vector or zero. When non-zero, only the half on this side of the axis (within the
    // tolerance): the side of a hole a pin bears on.
    Eigen::Vector3d facing = Eigen::Vector3d::Zero();
};

struct GroupRegion {
    std::string group;  // a vertex group of the mesh file (Gmsh physical group, selection flag)
};

struct Region {
    std::string name;
    std::variant<BoxRegion, CylinderRegion, GroupRegion> shape;
};

// Per vertex, 1 when it lies inside the region. Throws std::invalid_argument naming the region
// when it refers to a group the mesh file does not have.
std::vector<char> vertices_inside(const VolumeModel& model, const Region& region);

// The boundary triangles whose three vertices all lie inside the region.
std::vector<BoundaryTriangle> select_triangles(const VolumeModel& model,
                                               const std::vector<BoundaryTriangle>& boundary,
                                               const Region& region);

// The distinct vertices of a set of triangles, ascending.
std::vector<int> triangle_vertices(const std::vector<BoundaryTriangle>& triangles);

}  // namespace fibrecell::planner
