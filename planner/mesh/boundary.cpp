#include "planner/mesh/boundary.hpp"

#include <Eigen/Geometry>

#include <algorithm>

namespace fibrecell::planner {
namespace {

// Faces of a positively oriented tet (a,b,c,d), each counter-clockwise seen from outside.
constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

struct FaceKey {
    std::array<int, 3> sorted;
    int tet;
    int face;
};

}  // namespace

std::vector<BoundaryTriangle> boundary_triangles(const TetMesh& mesh) {
    std::vector<FaceKey> faces;
    faces.reserve(mesh.tets.size() * 4);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        for (int f = 0; f < 4; ++f) {
            std::array<int, 3> k = {mesh.tets[t][kFaces[f][0]], mesh.tets[t][kFaces[f][1]],
                                    mesh.tets[t][kFaces[f][2]]};
            std::sort(k.begin(), k.end());
            faces.push_back({k, static_cast<int>(t), f});
        }
    }
    std::sort(faces.begin(), faces.end(),
              [](const FaceKey& a, const FaceKey& b) { return a.sorted < b.sorted; });

    std::vector<BoundaryTriangle> out;
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].sorted == faces[i].sorted) ++j;
        if (j - i == 1) {
            const Tet& tet = mesh.tets[faces[i].tet];
            const int* f = kFaces[faces[i].face];
            out.push_back({{tet[f[0]], tet[f[1]], tet[f[2]]}, faces[i].tet});
        }
        i = j;
    }
    return out;
}

double triangle_area(const TetMesh& mesh, const BoundaryTriangle& t) {
    const Eigen::Vector3d& a = mesh.vertices[t.v[0]];
    return 0.5 * (mesh.vertices[t.v[1]] - a).cross(mesh.vertices[t.v[2]] - a).norm();
}

}  // namespace fibrecell::planner
