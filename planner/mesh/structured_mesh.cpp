#include "planner/mesh/structured_mesh.hpp"

#include <utility>

namespace fibrecell::planner {

TetMesh structured_tet_mesh(const StructuredMeshOptions& o) {
    // Plain variables, not a structured binding: the lambdas below capture them, which Clang
    // accepts only from version 16.
    const int nx = o.cells[0], ny = o.cells[1], nz = o.cells[2];
    auto grid_index = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
    const Eigen::Vector3d step = o.size.cwiseQuotient(Eigen::Vector3d(nx, ny, nz));

    std::vector<int> new_index(static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)), -1);
    TetMesh mesh;
    auto vertex = [&](int i, int j, int k) {
        int& idx = new_index[grid_index(i, j, k)];
        if (idx < 0) {
            idx = static_cast<int>(mesh.vertices.size());
            mesh.vertices.push_back(o.origin + step.cwiseProduct(Eigen::Vector3d(i, j, k)));
        }
        return idx;
    };
    // The 6 monotone paths from corner 0 to corner 7 (corner bit 0 = +x, 1 = +y, 2 = +z).
    constexpr int kPaths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                const Eigen::Vector3d centre =
                    o.origin + step.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                if (o.keep_cell && !o.keep_cell(centre)) continue;
                auto corner = [&](int c) {
                    return vertex(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
                };
                for (const auto& path : kPaths) {
                    Tet t = {corner(0), corner(path[0]), corner(path[1]), corner(7)};
                    if (signed_volume(mesh, t) < 0) std::swap(t[1], t[2]);
                    mesh.tets.push_back(t);
                }
            }
        }
    }
    return mesh;
}

}  // namespace fibrecell::planner
