#include "planner/mesh/boundary.hpp"

#include "planner/mesh/adjacency.hpp"

#include <Eigen/Geometry>

namespace fibrecell::planner {
namespace {

// Faces of a positively oriented tet, opposite local vertex f, counter-clockwise from outside.
constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

}  // namespace

std::vector<BoundaryTriangle> boundary_triangles(const TetMesh& mesh) {
    return boundary_triangles(mesh, face_neighbours(mesh));
}

std::vector<BoundaryTriangle> boundary_triangles(const TetMesh& mesh,
                                                 const FaceNeighbours& neighbours) {
    std::vector<BoundaryTriangle> out;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        for (int f = 0; f < 4; ++f) {
            if (neighbours[t][f] >= 0) continue;
            const Tet& tet = mesh.tets[t];
            out.push_back(
                {{tet[kFaces[f][0]], tet[kFaces[f][1]], tet[kFaces[f][2]]}, static_cast<int>(t)});
        }
    }
    return out;
}

double triangle_area(const TetMesh& mesh, const BoundaryTriangle& t) {
    const Eigen::Vector3d& a = mesh.vertices[t.v[0]];
    return 0.5 * (mesh.vertices[t.v[1]] - a).cross(mesh.vertices[t.v[2]] - a).norm();
}

}  // namespace fibrecell::planner
