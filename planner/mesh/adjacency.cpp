#include "planner/mesh/adjacency.hpp"

#include <algorithm>

namespace fibrecell::planner {
namespace {

// Local vertex indices of the face opposite local vertex f.
constexpr int kFaceVertices[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

struct FaceRef {
    std::array<int, 3> sorted;  // the face's vertex indices, ascending: equal for both sides
    int tet;
    int face;
};

}  // namespace

FaceNeighbours face_neighbours(const TetMesh& mesh) {
    std::vector<FaceRef> faces;
    faces.reserve(mesh.tets.size() * 4);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        for (int f = 0; f < 4; ++f) {
            const int* lv = kFaceVertices[f];
            std::array<int, 3> k = {mesh.tets[t][lv[0]], mesh.tets[t][lv[1]], mesh.tets[t][lv[2]]};
            std::sort(k.begin(), k.end());
            faces.push_back({k, static_cast<int>(t), f});
        }
    }
    std::sort(faces.begin(), faces.end(),
              [](const FaceRef& a, const FaceRef& b) { return a.sorted < b.sorted; });

    FaceNeighbours out(mesh.tets.size(), {-1, -1, -1, -1});
    for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
        // In a valid (manifold) mesh a face is shared by at most two tets.
        if (faces[i].sorted == faces[i + 1].sorted) {
            out[faces[i].tet][faces[i].face] = faces[i + 1].tet;
            out[faces[i + 1].tet][faces[i + 1].face] = faces[i].tet;
            ++i;
        }
    }
    return out;
}

CsrGraph vertex_to_tets(const TetMesh& mesh) {
    CsrGraph g;
    g.offsets.assign(mesh.vertices.size() + 1, 0);
    for (const Tet& t : mesh.tets)
        for (int v : t) ++g.offsets[v + 1];
    for (std::size_t i = 1; i < g.offsets.size(); ++i) g.offsets[i] += g.offsets[i - 1];
    g.targets.resize(g.offsets.back());
    std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        for (int v : mesh.tets[t]) g.targets[fill[v]++] = static_cast<int>(t);
    return g;
}

CsrGraph vertex_sharing_neighbours(const TetMesh& mesh) {
    const CsrGraph by_vertex = vertex_to_tets(mesh);
    CsrGraph g;
    g.offsets.reserve(mesh.tets.size() + 1);
    g.offsets.push_back(0);
    g.targets.reserve(mesh.tets.size() * 64);
    // `seen[u] == t` marks u as already listed for tet t: dedupes without sorting a union.
    std::vector<int> seen(mesh.tets.size(), -1);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const int ti = static_cast<int>(t);
        seen[t] = ti;
        const std::size_t first = g.targets.size();
        for (int v : mesh.tets[t]) {
            for (int u : by_vertex.neighbours(v)) {
                if (seen[u] == ti) continue;
                seen[u] = ti;
                g.targets.push_back(u);
            }
        }
        std::sort(g.targets.begin() + static_cast<std::ptrdiff_t>(first), g.targets.end());
        g.offsets.push_back(static_cast<int>(g.targets.size()));
    }
    return g;
}

}  // namespace fibrecell::planner
