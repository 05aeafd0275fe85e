#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Geometry>

namespace fibrecell::planner {

double signed_volume(const TetMesh& mesh, const Tet& t) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    return (mesh.vertices[t[1]] - a).dot((mesh.vertices[t[2]] - a).cross(mesh.vertices[t[3]] - a)) /
           6.0;
}

}  // namespace fibrecell::planner
