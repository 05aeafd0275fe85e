#pragma once
// Hand-built layer meshes for the per-layer field tests: a triangulated rectangle (optionally
// with a square hole) where triangle f was cut from tet f.

#include "planner/layers/layer_mesh.hpp"

#include <functional>

namespace fibrecell::planner::layer_test {

inline LayerMesh grid_layer(double width, double height, int nx, int ny,
                            const std::function<bool(const Eigen::Vector2d&)>& keep_cell = {}) {
    LayerMesh m;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) m.vertices.emplace_back(width * i / nx, height * j / ny);
    auto id = [&](int i, int j) { return i + (nx + 1) * j; };
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const Eigen::Vector2d centre(width * (i + 0.5) / nx, height * (j + 0.5) / ny);
            if (keep_cell && !keep_cell(centre)) continue;
            // Alternate the diagonal so the mesh has no preferred direction.
            if ((i + j) % 2 == 0) {
                m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            } else {
                m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
                m.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
            }
        }
    }
    for (std::size_t f = 0; f < m.triangles.size(); ++f)
        m.triangle_tet.push_back(static_cast<int>(f));
    return m;
}

inline Eigen::Vector2d centre(const LayerMesh& m, int f) {
    const auto& t = m.triangles[f];
    return (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
}

}  // namespace fibrecell::planner::layer_test
