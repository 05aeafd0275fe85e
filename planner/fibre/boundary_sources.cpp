#include "planner/fibre/boundary_sources.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>

namespace fibrecell::planner {
namespace {

// p lies on the triangle (within tol [mm] of its plane, inside its edges).
bool on_face(const Eigen::Vector3d& p, const std::array<Eigen::Vector3d, 3>& f, double tol) {
    const Eigen::Vector3d n = (f[1] - f[0]).cross(f[2] - f[0]);
    const double area2 = n.norm();
    if (area2 == 0) return false;
    if (std::abs(n.dot(p - f[0])) / area2 > tol) return false;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d e = f[(k + 1) % 3] - f[k];
        // Signed distance of p from edge k inside the face plane, positive inside.
        if (n.cross(e).dot(p - f[k]) / (area2 * e.norm()) < -tol) return false;
    }
    return true;
}

}  // namespace

SelectedFaces selected_faces(const TetMesh& placed, const std::vector<BoundaryTriangle>& faces) {
    SelectedFaces out;
    for (const BoundaryTriangle& t : faces)
        out.by_tet[t.tet].push_back(
            {placed.vertices[t.v[0]], placed.vertices[t.v[1]], placed.vertices[t.v[2]]});
    return out;
}

std::vector<std::array<int, 2>> selected_outline_edges(const LayerMesh& layer,
                                                       const SelectedFaces& faces) {
    if (faces.empty()) return {};
    // Outline edges are used by one triangle; remember which.
    std::map<std::pair<int, int>, int> edge_triangle;  // edge -> triangle, or -1 when shared
    for (int f = 0; f < static_cast<int>(layer.triangles.size()); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = layer.triangles[f][k], b = layer.triangles[f][(k + 1) % 3];
            auto [it, fresh] = edge_triangle.try_emplace({std::min(a, b), std::max(a, b)}, f);
            if (!fresh) it->second = -1;
        }
    const double tol = 1e-6 * (1 + std::abs(layer.z));  // slicing round-off [mm]
    auto lift = [&](int v) {
        return Eigen::Vector3d(layer.vertices[v].x(), layer.vertices[v].y(), layer.z);
    };
    std::vector<std::array<int, 2>> edges;
    for (const auto& [edge, f] : edge_triangle) {
        if (f < 0) continue;
        const auto it = faces.by_tet.find(layer.triangle_tet[f]);
        if (it == faces.by_tet.end()) continue;
        const Eigen::Vector3d a = lift(edge.first), b = lift(edge.second);
        for (const auto& face : it->second)
            if (on_face(a, face, tol) && on_face(b, face, tol)) {
                edges.push_back({edge.first, edge.second});
                break;
            }
    }
    return edges;  // in the map's order: ascending
}

}  // namespace fibrecell::planner
