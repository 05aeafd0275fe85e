#pragma once
// Procedural meshes and region pickers for the FEA tests (no mesh reader involved).

#include "planner/fea/linear_elastic.hpp"
#include "planner/mesh/boundary.hpp"
#include "planner/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace fibrecell::planner::fea_test {

inline constexpr double kTol = 1e-9;  // [mm], for picking vertices on a face

// Position [mm] of grid point (i, j, k).
using GridMap = std::function<Eigen::Vector3d(int i, int j, int k)>;

// ni x nj x nk hexahedral cells mapped through `position`, each split into 6 tets around its
// main diagonal (Kuhn: conforming between neighbours, also across a periodic seam). With
// wrap_i the i direction is closed: i = ni is the same grid point as i = 0.
inline TetMesh structured_tets(int ni, int nj, int nk, const GridMap& position,
                               bool wrap_i = false) {
    const int pi = wrap_i ? ni : ni + 1;  // grid points along i
    auto id = [&](int i, int j, int k) { return (i % pi) + pi * (j + (nj + 1) * k); };
    TetMesh m;
    for (int k = 0; k <= nk; ++k)
        for (int j = 0; j <= nj; ++j)
            for (int i = 0; i < pi; ++i) m.vertices.push_back(position(i, j, k));
    // Corner c of a cell has offsets (c & 1, c >> 1 & 1, c >> 2 & 1); paths 0 -> 7.
    const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
    for (int k = 0; k < nk; ++k)
        for (int j = 0; j < nj; ++j)
            for (int i = 0; i < ni; ++i) {
                auto corner = [&](int c) {
                    return id(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
                };
                for (auto [a, b] : paths) {
                    Tet t = {corner(0), corner(a), corner(b), corner(7)};
                    if (signed_volume(m, t) < 0) std::swap(t[1], t[2]);
                    m.tets.push_back(t);
                }
            }
    return m;
}

// Box [0, size] split into nx x ny x nz cells.
inline TetMesh box_mesh(const Eigen::Vector3d& size, int nx, int ny, int nz) {
    return structured_tets(nx, ny, nz, [&](int i, int j, int k) {
        return Eigen::Vector3d(size.x() * i / nx, size.y() * j / ny, size.z() * k / nz);
    });
}

// One mesh of several, vertices at the same position (to 1e-6 mm) merged. The parts must meet
// conformingly (same vertices and face diagonals on shared faces).
inline TetMesh merge_meshes(const std::vector<TetMesh>& parts) {
    TetMesh m;
    std::map<std::array<long long, 3>, int> index;  // rounded position -> merged vertex
    for (const TetMesh& part : parts) {
        std::vector<int> merged(part.vertex_count());
        for (std::size_t v = 0; v < part.vertex_count(); ++v) {
            const Eigen::Vector3d& p = part.vertices[v];
            const std::array<long long, 3> key = {
                std::llround(p.x() * 1e6), std::llround(p.y() * 1e6), std::llround(p.z() * 1e6)};
            const auto [it, added] = index.emplace(key, static_cast<int>(m.vertex_count()));
            if (added) m.vertices.push_back(p);
            merged[v] = it->second;
        }
        for (const Tet& t : part.tets)
            m.tets.push_back({merged[t[0]], merged[t[1]], merged[t[2]], merged[t[3]]});
    }
    return m;
}

// A plate with a central circular hole, centred on the origin in x and y, z in [0, thickness]:
// an O-grid (rings graded towards the hole, every 8th spoke on a corner of the square
// [-w/2, w/2]^2) with straight extensions of length `extension` on both x ends.
struct HolePlate {
    double hole_radius = 5;     // a [mm]
    double width = 100;         // w, along y [mm]
    double extension = 100;     // added beyond the square on each x end [mm]
    double thickness = 1;       // [mm]
    int spokes = 96;            // cells around the hole, a multiple of 8
    int rings = 24;             // cells from the hole to the square
    double ring_growth = 1.15;  // ratio of neighbouring ring widths
    int extension_cells = 16;   // cells along x in each extension
    int layers = 1;             // cells through the thickness
    double length() const { return width + 2 * extension; }
};

inline TetMesh hole_plate_mesh(const HolePlate& p) {
    const double pi = std::numbers::pi;
    const double half = p.width / 2;
    auto z = [&](int k) { return p.thickness * k / p.layers; };
    const TetMesh ring = structured_tets(
        p.spokes, p.rings, p.layers,
        [&](int i, int j, int k) {
            const double angle = 2 * pi * i / p.spokes;
            const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
            const Eigen::Vector2d inner = p.hole_radius * dir;
            const Eigen::Vector2d outer =
                dir * (half / std::max(std::abs(dir.x()), std::abs(dir.y())));
            const double s =
                (std::pow(p.ring_growth, j) - 1) / (std::pow(p.ring_growth, p.rings) - 1);
            const Eigen::Vector2d q = inner + s * (outer - inner);
            return Eigen::Vector3d(q.x(), q.y(), z(k));
        },
        true);
    // The O-grid's spokes meet the square's x = +-w/2 sides at these y; the extensions reuse them.
    // The left one runs its j axis downwards so the face diagonals match the O-grid's.
    const int side = p.spokes / 4;
    auto side_y = [&](int j) { return half * std::tan(-pi / 4 + 2 * pi * j / p.spokes); };
    const int n = p.extension_cells;
    const TetMesh right = structured_tets(n, side, p.layers, [&](int i, int j, int k) {
        return Eigen::Vector3d(half + p.extension * i / n, side_y(j), z(k));
    });
    const TetMesh left = structured_tets(n, side, p.layers, [&](int i, int j, int k) {
        return Eigen::Vector3d(-half - p.extension * (n - i) / n, -side_y(j), z(k));
    });
    return merge_meshes({ring, right, left});
}

inline std::vector<int> vertices_where(const TetMesh& m,
                                       const std::function<bool(const Eigen::Vector3d&)>& keep) {
    std::vector<int> out;
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        if (keep(m.vertices[v])) out.push_back(static_cast<int>(v));
    return out;
}

// Boundary triangles whose three vertices all satisfy `keep`.
inline std::vector<BoundaryTriangle> boundary_where(
    const TetMesh& m, const std::function<bool(const Eigen::Vector3d&)>& keep) {
    std::vector<BoundaryTriangle> out;
    for (const BoundaryTriangle& t : boundary_triangles(m))
        if (keep(m.vertices[t.v[0]]) && keep(m.vertices[t.v[1]]) && keep(m.vertices[t.v[2]]))
            out.push_back(t);
    return out;
}

inline Eigen::Vector3d centroid(const TetMesh& m, const Tet& t) {
    return 0.25 * (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]] + m.vertices[t[3]]);
}

inline Eigen::Vector3d sum(const std::vector<Eigen::Vector3d>& vectors) {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : vectors) s += v;
    return s;
}

}  // namespace fibrecell::planner::fea_test
