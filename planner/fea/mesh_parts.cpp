#include "planner/fea/mesh_parts.hpp"

#include <numeric>

namespace fibrecell::planner {
namespace {

// Union-find with path halving; roots are the smallest vertex of their set.
int find_root(std::vector<int>& parent, int v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

}  // namespace

MeshParts mesh_parts(const TetMesh& mesh) {
    const int n = static_cast<int>(mesh.vertex_count());
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<char> used(n, 0);
    for (const Tet& t : mesh.tets) {
        for (int v : t) used[v] = 1;
        for (int a = 1; a < 4; ++a) {
            const int r0 = find_root(parent, t[0]);
            const int ra = find_root(parent, t[a]);
            if (r0 < ra) parent[ra] = r0;
            if (ra < r0) parent[r0] = ra;
        }
    }
    MeshParts parts;
    parts.part_of_vertex.assign(n, -1);
    std::vector<int> part_of_root(n, -1);
    for (int v = 0; v < n; ++v) {
        if (!used[v]) continue;
        const int r = find_root(parent, v);
        if (part_of_root[r] < 0) part_of_root[r] = parts.count++;
        parts.part_of_vertex[v] = part_of_root[r];
    }
    return parts;
}

}  // namespace fibrecell::planner
