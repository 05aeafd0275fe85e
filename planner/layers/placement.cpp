#include "planner/layers/placement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fibrecell::planner {

namespace {

// Rotation about one axis by `deg`, exact for multiples of 90 degrees so that a part turned on its
// side keeps its vertex layers exactly flat (cos(pi/2) is 6e-17 in floating point).
Eigen::Matrix3d axis_rotation(int axis, double deg) {
    double c = 0, s = 0;
    const double quarter_turns = deg / 90.0;
    if (quarter_turns == std::round(quarter_turns)) {
        const int q = static_cast<int>(std::fmod(quarter_turns, 4.0) + 4.0) % 4;
        constexpr double kCos[4] = {1, 0, -1, 0};
        constexpr double kSin[4] = {0, 1, 0, -1};
        c = kCos[q];
        s = kSin[q];
    } else {
        const double rad = deg * M_PI / 180.0;
        c = std::cos(rad);
        s = std::sin(rad);
    }
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;  // the plane the rotation turns
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    r(i, i) = c;
    r(i, j) = -s;
    r(j, i) = s;
    r(j, j) = c;
    return r;
}

}  // namespace

Placement placement_for(const TetMesh& mesh, const PlacementSpec& spec) {
    if (mesh.vertices.empty()) throw std::invalid_argument("placement: the mesh has no vertices");
    if (!spec.rotate_deg.allFinite())
        throw std::invalid_argument("placement: rotate_deg is not finite");
    if (!spec.position_mm.allFinite())
        throw std::invalid_argument("placement: position_mm is not finite");

    Placement placement;
    placement.rotation = axis_rotation(2, spec.rotate_deg.z()) *
                         axis_rotation(1, spec.rotate_deg.y()) *
                         axis_rotation(0, spec.rotate_deg.x());
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
    Eigen::Vector3d hi = -lo;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const Eigen::Vector3d& p = mesh.vertices[v];
        if (!p.allFinite())
            throw std::invalid_argument("placement: vertex " + std::to_string(v) +
                                        " is not finite");
        const Eigen::Vector3d q = placement.rotation * p;
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    placement.translation = Eigen::Vector3d(spec.position_mm.x() - centre.x(),
                                            spec.position_mm.y() - centre.y(), -lo.z());
    return placement;
}

TetMesh place_mesh(const TetMesh& mesh, const Placement& placement) {
    TetMesh placed;
    placed.tets = mesh.tets;
    placed.vertices.reserve(mesh.vertices.size());
    for (const Eigen::Vector3d& p : mesh.vertices) placed.vertices.push_back(placement.apply(p));
    return placed;
}

std::vector<Eigen::Vector3d> rotate_vectors(std::span<const Eigen::Vector3d> vectors,
                                            const Placement& placement) {
    std::vector<Eigen::Vector3d> rotated;
    rotated.reserve(vectors.size());
    for (const Eigen::Vector3d& v : vectors) rotated.push_back(placement.rotation * v);
    return rotated;
}

double part_height(const TetMesh& placed) {
    if (placed.vertices.empty())
        throw std::invalid_argument("part_height: the mesh has no vertices");
    double lo = INFINITY, hi = -INFINITY;
    for (const Eigen::Vector3d& p : placed.vertices) {
        lo = std::min(lo, p.z());
        hi = std::max(hi, p.z());
    }
    return hi - lo;
}

}  // namespace fibrecell::planner
